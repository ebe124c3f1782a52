// terracal: soil calibration and vehicle-mobility tool. Exit codes (docs/architecture.md, "Errors and outputs"):
// 0 success; 2 bad input (the message names file, line/key, value and what was expected);
// 1 a run that failed (the message says which step and why).
#include <algorithm>
#include <cstdio>
#include <exception>
#include <map>
#include <numeric>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include "apps/commands.hpp"
#include "core/errors.hpp"
#include "terracal_version.hpp"

namespace {

// Levenshtein distance: how many letters to insert, delete or change to turn a into b.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  std::iota(row.begin(), row.end(), 0);
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// " (did you mean 'calibrate'?)" when one of `names` is a likely typo of `word` (at most two
// letters off, and fewer than a third of the word), else "".
std::string did_you_mean(const std::string& word, const std::vector<std::string>& names) {
  std::string best;
  std::size_t best_distance = std::min<std::size_t>(3, (word.size() + 2) / 3);
  for (const auto& n : names) {
    const std::size_t d = edit_distance(word, n);
    if (d < best_distance) best = n, best_distance = d;
  }
  return best.empty() ? "" : fmt::format(" (did you mean '{}'?)", best);
}

std::vector<std::string> command_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const auto* sub : app.get_subcommands([](const CLI::App*) { return true; })) names.push_back(sub->get_name());
  return names;
}

std::vector<std::string> option_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const auto* opt : app.get_options())
    for (const auto& n : opt->get_lnames()) names.push_back("--" + n);
  return names;
}

// CLI11 says "The following argument was not expected: frobnicate"; this says whether it was taken
// for a command or an option, what was expected, and the nearest name when it looks like a typo.
std::string unexpected_message(const CLI::App& app) {
  const auto parsed = app.get_subcommands();
  const CLI::App& at = parsed.empty() || !app.remaining().empty() ? app : *parsed.back();
  const std::vector<std::string> extras = at.remaining();
  const std::string found = extras.empty() ? "" : extras.front();
  const std::string name = &at == &app ? "terracal" : "terracal " + at.get_name();
  if (found.starts_with("-")) {
    const std::string option = found.substr(0, found.find('='));
    return fmt::format("{}: unknown option '{}'{}; '{} --help' lists the options", name, option,
                       did_you_mean(option, option_names(at)), name);
  }
  if (&at == &app)
    return fmt::format("terracal: unknown command '{}'{}; expected one of {}", found,
                       did_you_mean(found, command_names(app)), fmt::join(command_names(app), ", "));
  return fmt::format("{}: unexpected argument '{}' (the inputs are given as options); '{} --help' lists them", name,
                     found, name);
}

// The message and exit code for a command line CLI11 refused: 0 for --help and --version, else 2.
int command_line_refused(const CLI::App& app, const CLI::ParseError& e) {
  if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
  // A word CLI11 did not take is reported first, whichever error CLI11 raised: it is often the
  // reason for that error ("--plat" leaves --plate missing, "frobnicate" leaves no command).
  const auto parsed = app.get_subcommands();
  if (!app.remaining(true).empty()) {
    fmt::print(stderr, "{}\n", unexpected_message(app));
  } else if (parsed.empty()) {
    fmt::print(stderr, "terracal: a command is required; expected one of {} ('terracal --help' describes them)\n",
               fmt::join(command_names(app), ", "));
  } else {  // CLI11's own words (a missing or invalid option), naming the command
    const std::string name = "terracal " + parsed.back()->get_name();
    fmt::print(stderr, "{}: {}; '{} --help' lists the options\n", name, e.what(), name);
  }
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"terracal: calibrated soil models (SCM) and reduced-order vehicles from high-fidelity virtual tests"};
  app.set_version_flag("--version", std::string("terracal ") + TERRACAL_VERSION);
  app.require_subcommand(1);
  std::map<CLI::App*, terracal::app::Command> commands;
  auto add = [&](auto adder, const char* name) {
    terracal::app::Command c = adder(app);
    commands[app.get_subcommand(name)] = c;
  };
  add(terracal::app::add_calibrate, "calibrate");
  add(terracal::app::add_demo, "demo");
  add(terracal::app::add_synthesize, "synthesize");
  add(terracal::app::add_crm, "crm");
  add(terracal::app::add_bevameter, "bevameter");
  add(terracal::app::add_wheel, "wheel");
  add(terracal::app::add_wheel_table, "wheel-table");
  add(terracal::app::add_pipeline, "pipeline");
  add(terracal::app::add_rom, "rom");
  add(terracal::app::add_vehicle, "vehicle");
  add(terracal::app::add_calibrate_rom, "calibrate-rom");
  add(terracal::app::add_validate_rom, "validate-rom");
  add(terracal::app::add_pipeline_rom, "pipeline-rom");
  add(terracal::app::add_campaign, "campaign");
  add(terracal::app::add_study, "study");
  // Progress and messages go to stderr; stdout carries the summary table only.
  spdlog::set_default_logger(spdlog::stderr_color_mt("terracal"));
  spdlog::set_pattern("[%H:%M:%S] %^%l%$ %v");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return command_line_refused(app, e);
  }
  try {
    for (auto* sub : app.get_subcommands()) return commands.at(sub)();
  } catch (const terracal::InputError& e) {
    spdlog::error("{}", e.what());
    return 2;
  } catch (const terracal::RunError& e) {
    spdlog::error("{}", e.what());
    return 1;
  } catch (const std::exception& e) {
    spdlog::error("run failed: {}", e.what());
    return 1;
  }
  return 0;
}
