// `terracal rom`: one reduced-order vehicle (11 or 18 DOF) driven by a driver file or a built-in
// manoeuvre; writes trajectory.csv, trajectory.png and run.json.
#include <filesystem>
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "apps/cli_checks.hpp"
#include "apps/commands.hpp"
#include "apps/out_dir.hpp"
#include "apps/report_plots.hpp"
#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "rom/rom_run.hpp"
#include "rom/rom_vehicle_json.hpp"
#include "rom/trajectory_csv.hpp"

namespace terracal::app {

namespace {
struct RomArgs {
  rom::RomRunOptions run;
  std::string vehicle, tire, inputs, maneuver, out;
  double friction = 1.0, gravity = 9.81;
  bool plots = true;
};

const std::map<std::string, rom::RomModel> kModels = {{"11dof", rom::RomModel::k11Dof},
                                                      {"18dof", rom::RomModel::k18Dof}};
const std::map<std::string, rom::RomIntegrator> kIntegrators = {{"cvodes", rom::RomIntegrator::kCvodes},
                                                                {"half-implicit", rom::RomIntegrator::kHalfImplicit}};
}  // namespace

Command add_rom(CLI::App& app) {
  auto* sub = app.add_subcommand("rom", "A reduced-order vehicle (11/18 DOF) on rigid ground; writes trajectory.csv");
  auto a = std::make_shared<RomArgs>();
  add_choice(sub, "--model", a->run.model, kModels, "vehicle model")->required()->default_str("");
  sub->add_option("--vehicle", a->vehicle, "vehicle file (JSON, ours or LFDM's) or preset: hmmwv, sedan")->required();
  sub->add_option("--tire", a->tire, "TMeasy tire file replacing the vehicle's (needed with an LFDM vehicle file)");
  auto* inputs = sub->add_option("--inputs", a->inputs, "driver file: rows 'time steering throttle braking'");
  auto* maneuver = sub->add_option("--maneuver", a->maneuver, "built-in manoeuvre (JSON, docs/formats.md)");
  inputs->excludes(maneuver);
  sub->add_option("--end-time", a->run.end_time,
                  "simulated seconds (default: the driver file's last time or the "
                  "manoeuvre's end_time)")
      ->check(in_range(Range{0, 1e5, true, false}));
  sub->add_option("--initial-speed", a->run.initial_speed, "initial forward speed [m/s] (negative: backwards)")
      ->check(in_range(Range{-100, 100, false, false}));
  add_choice(sub, "--integrator", a->run.integrator, kIntegrators, "time integrator")->capture_default_str();
  sub->add_option("--step", a->run.step, "fixed step of the half-implicit scheme [s]")
      ->check(in_range(Range{1e-6, 0.1, false, false}))
      ->capture_default_str();
  sub->add_option("--rtol", a->run.rtol, "CVODES relative tolerance")
      ->check(in_range(Range{1e-12, 1e-1, false, false}))
      ->capture_default_str();
  sub->add_option("--atol", a->run.atol, "CVODES absolute tolerance")
      ->check(in_range(Range{1e-14, 1e-1, false, false}))
      ->capture_default_str();
  sub->add_option("--output-rate", a->run.output_rate, "samples per second in trajectory.csv [Hz]")
      ->check(in_range(Range{0.1, 1e4, false, false}))
      ->capture_default_str();
  sub->add_option("--friction", a->friction, "road friction relative to the tire data's")
      ->check(in_range(Range{0.01, 2, false, false}))
      ->capture_default_str();
  sub->add_option("--gravity", a->gravity, "gravitational acceleration [m/s^2] (Moon: 1.62)")
      ->check(in_range(Range{0.1, 30, false, false}))
      ->capture_default_str();
  sub->add_flag("!--no-plots", a->plots, "skip trajectory.png");
  sub->add_option("--out", a->out, "output folder")->required();
  return [a, sub] {
    const OutDir out = prepare_out_dir("--out", a->out);
    if (a->inputs.empty() == a->maneuver.empty())
      throw InputError("terracal rom: give the driver as --inputs DRIVER.txt or --maneuver M.json (one of them)");
    rom::RomVehicle vehicle = rom::load_rom_vehicle(a->vehicle, a->tire);
    vehicle.friction = a->friction;
    vehicle.gravity = a->gravity;
    rom::validate(vehicle, a->vehicle);
    rom::RomRunOptions run = a->run;
    const bool end_given = sub->count("--end-time") > 0;
    std::unique_ptr<DriverSeries> series;
    std::unique_ptr<Maneuver> maneuver;
    rom::RomDriver driver;
    if (!a->inputs.empty()) {
      series = std::make_unique<DriverSeries>(DriverSeries::read(a->inputs));
      driver.series = series.get();
      if (!end_given) run.end_time = series->end_time();
    } else {
      const ManeuverVehicle mv{vehicle.wheelbase(), vehicle.max_steer, std::max(vehicle.track[0], vehicle.track[1])};
      maneuver = std::make_unique<Maneuver>(Maneuver::read(a->maneuver, mv));
      driver.maneuver = maneuver.get();
      if (!end_given) run.end_time = maneuver->end_time();
      if (sub->count("--initial-speed") == 0) run.initial_speed = maneuver->initial_speed();
    }
    if (run.integrator == rom::RomIntegrator::kHalfImplicit && run.step > 1.0 / run.output_rate)
      throw InputError(fmt::format("--step {} s: must not exceed the output interval 1/--output-rate = {} s", run.step,
                                   1.0 / run.output_rate));
    if (!(run.end_time > 0)) throw InputError(fmt::format("--end-time {}: must be positive", run.end_time));
    std::filesystem::create_directories(a->out);
    const rom::RomRunResult r = rom::run_rom(vehicle, driver, run);
    rom::write_trajectory_csv(a->out + "/trajectory.csv", r.samples);
    const nlohmann::json j = {{"model", rom::model_name(run.model)},
                              {"integrator", rom::integrator_name(run.integrator)},
                              {"vehicle", a->vehicle},
                              {"end_time", run.end_time},
                              {"steps", r.steps},
                              {"rhs_evaluations", r.rhs_evaluations},
                              {"wall_seconds", r.wall_seconds},
                              {"real_time_factor", run.end_time / std::max(r.wall_seconds, 1e-12)}};
    write_text_atomically(a->out + "/run.json", j.dump(2) + "\n");
    if (a->plots)
      plot_trajectory(a->out, fmt::format("{} {} ({})", a->vehicle, rom::model_name(run.model),
                                          rom::integrator_name(run.integrator)));
    fmt::print("rom ({}, {}): {:.3g} s simulated in {:.3g} s wall ({:.0f}x real time); written to {}/trajectory.csv\n",
               rom::model_name(run.model), rom::integrator_name(run.integrator), run.end_time, r.wall_seconds,
               run.end_time / std::max(r.wall_seconds, 1e-12), a->out);
    return 0;
  };
}

}  // namespace terracal::app
