#include "apps/job_options.hpp"

#include <filesystem>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "apps/commands.hpp"
#include "core/errors.hpp"
#include "core/text_check.hpp"

namespace terracal::app {
namespace fs = std::filesystem;
namespace {

using Json = nlohmann::ordered_json;

// Registers `command` on `app`; the returned function owns what its options write into.
Command command_of(CLI::App& app, const std::string& command) {
  if (command == "bevameter") return add_bevameter(app);
  if (command == "calibrate") return add_calibrate(app);
  if (command == "wheel") return add_wheel(app);
  if (command == "rom") return add_rom(app);
  if (command == "wheel-table") return add_wheel_table(app);
  if (command == "vehicle") return add_vehicle(app);
  throw std::logic_error("command_of: no job runs 'terracal " + command + "'");
}

std::string text_of(const Json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_integer()) return fmt::format("{}", v.get<long long>());
  if (v.is_number()) return fmt::format("{}", v.get<double>());
  return v.dump();
}

std::vector<std::string> option_words(const CLI::Option& o, const Json& v) {
  if (!v.is_array()) return {text_of(v)};
  std::vector<std::string> words;
  for (const auto& e : v) words.push_back(text_of(e));
  if (o.get_expected_max() > 1) return words;
  std::string joined;
  for (const auto& w : words) joined += (joined.empty() ? "" : ",") + w;
  return {joined};
}

}  // namespace

void check_command_options(const std::string& spec, const std::string& where, const std::string& command,
                           const Json& options, const std::set<std::string>& reserved) {
  CLI::App app;
  const Command keep = command_of(app, command);  // owns the variables the options write into
  CLI::App* sub = app.get_subcommand(command);
  for (const auto& [k, v] : options.items()) {
    const std::string key = where + k;
    if (reserved.count(k)) throw InputError(fmt::format("{}: key '{}': set by terracal itself here", spec, key));
    CLI::Option* o = sub->get_option_no_throw("--" + k);
    if (!o) throw InputError(fmt::format("{}: key '{}': 'terracal {}' has no option --{}", spec, key, command, k));
    if (o->get_expected_max() == 0) {  // a flag
      if (!v.is_boolean())
        throw InputError(fmt::format("{}: key '{}': --{} is a flag; expected true or false, found {}", spec, key, k,
                                     excerpt(v.dump())));
      continue;
    }
    if (!(v.is_array() || v.is_string() || v.is_number()))
      throw InputError(fmt::format("{}: key '{}': expected a number, a string or a list, found {}", spec, key,
                                   excerpt(v.dump())));
    try {
      o->add_result(option_words(*o, v));
      o->run_callback();
    } catch (const CLI::Error& e) {
      throw InputError(fmt::format("{}: key '{}': value {} refused by terracal {} --{}: {}", spec, key,
                                   excerpt(v.dump()), command, k, e.what()));
    }
  }
}

std::vector<std::string> command_option_words(const std::string& command, const Json& options) {
  CLI::App app;
  const Command keep = command_of(app, command);
  const CLI::App* sub = app.get_subcommand(command);
  std::vector<std::string> args;
  for (const auto& [k, v] : options.items()) {
    const CLI::Option* o = sub->get_option("--" + k);
    if (o->get_expected_max() == 0) {
      if (v.get<bool>()) args.push_back("--" + k);
      continue;
    }
    args.push_back("--" + k);
    for (auto& w : option_words(*o, v)) args.push_back(std::move(w));
  }
  return args;
}

std::string spec_file(const std::string& spec, const std::string& key, const Json& v) {
  if (!v.is_string() || v.get<std::string>().empty())
    throw InputError(fmt::format("{}: key '{}': expected a file name (string), found {}", spec, key, excerpt(v.dump())));
  fs::path p(v.get<std::string>());
  if (p.is_relative()) p = fs::path(spec).parent_path() / p;
  if (!fs::is_regular_file(p))
    throw InputError(fmt::format("{}: key '{}': file '{}' not found", spec, key, p.string()));
  return fs::absolute(p).lexically_normal().string();
}

void refuse_unknown(const std::string& spec, const std::string& where, const Json& o, const std::set<std::string>& ok) {
  for (const auto& [k, v] : o.items())
    if (!ok.count(k))
      throw InputError(fmt::format("{}: unknown key '{}{}'; expected one of {}", spec, where, k, fmt::join(ok, ", ")));
}

}  // namespace terracal::app
