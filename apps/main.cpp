// terracal: soil calibration and vehicle-mobility tool. Exit codes (docs/architecture.md, "Errors and outputs"):
// 0 success; 2 bad input (the message names file, line/key, value and what was expected);
// 1 a run that failed (the message says which step and why).
#include <cstdio>
#include <exception>
#include <map>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include "apps/commands.hpp"
#include "core/errors.hpp"
#include "terracal_version.hpp"

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
  add(terracal::app::add_pipeline, "pipeline");
  // Progress and messages go to stderr; stdout carries the summary table only.
  spdlog::set_default_logger(spdlog::stderr_color_mt("terracal"));
  spdlog::set_pattern("[%H:%M:%S] %^%l%$ %v");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
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
