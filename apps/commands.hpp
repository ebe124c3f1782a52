#pragma once
// The subcommands of the terracal program. Each registers its options on the CLI11 app and
// returns the function that runs it once parsing succeeded.
#include <functional>

#include <CLI/CLI.hpp>

namespace terracal::app {

using Command = std::function<int()>;

Command add_calibrate(CLI::App& app);
Command add_demo(CLI::App& app);
Command add_synthesize(CLI::App& app);
Command add_crm(CLI::App& app);
Command add_bevameter(CLI::App& app);
Command add_wheel(CLI::App& app);
Command add_wheel_table(CLI::App& app);
Command add_pipeline(CLI::App& app);
Command add_rom(CLI::App& app);
Command add_vehicle(CLI::App& app);
Command add_calibrate_rom(CLI::App& app);
Command add_validate_rom(CLI::App& app);
Command add_pipeline_rom(CLI::App& app);
Command add_campaign(CLI::App& app);
Command add_study(CLI::App& app);

}  // namespace terracal::app
