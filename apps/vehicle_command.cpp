// `terracal vehicle`: the full multibody vehicle on rigid ground, driven by a driver file or a built-in
// manoeuvre; writes trajectory.csv (as `terracal rom`), wheels.csv, inputs.txt (the driver inputs
// applied, as a driver file), run.json and trajectory.png; with
// --vtu, ParaView snapshots of the bodies in vtu/ (vehicle_NNNNN.vtu and vehicle.pvd).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "apps/cli_checks.hpp"
#include "apps/commands.hpp"
#include "apps/out_dir.hpp"
#include "apps/report_plots.hpp"
#include "apps/terrain_options.hpp"
#include "apps/vehicle_outputs.hpp"
#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "highfi/vehicle/vehicle_run.hpp"
#include "highfi/vehicle/vehicle_vtu.hpp"
#include "lowfi/scm_soil.hpp"
#include "lowfi/scm_terrain.hpp"

namespace terracal::app {
namespace {
struct VehicleArgs {
  vehicle::VehicleRunOptions run;
  std::string vehicle, terrain = "rigid", scm, maneuver, inputs, out;
  bool plots = true, vtu = false;
  std::vector<std::string> scm_effects = {lowfi::ScmDamping::kName};
};

void add_options(CLI::App* sub, VehicleArgs& a) {
  sub->add_option("--vehicle", a.vehicle, "full vehicle file (JSON) or preset: hmmwv")->required();
  sub->add_option("--terrain", a.terrain, "rigid (flat ground) or scm")
      ->check(CLI::IsMember({"rigid", "scm"}))
      ->capture_default_str();
  sub->add_option("--scm", a.scm,
                  "SCM parameter set (Chrono SCM JSON or terracal's scm_params.json) for --terrain scm");
  a.run.scm.grid = 0.02;  // a vehicle's wheels: half a metre of radius, a quarter of width
  sub->add_option("--scm-grid", a.run.scm.grid, "SCM grid spacing [m]")
      ->check(in_range(RigRanges::kScmGrid))
      ->capture_default_str();
  sub->add_option("--scm-step", a.run.scm.time_step, "SCM step: the soil's wrenches are held this long [s]")
      ->check(in_range(Range{1e-5, 0.01, false, false}))
      ->capture_default_str();
  sub->add_option("--scm-effects", a.scm_effects,
                  fmt::format("SCM effects: {}, or none", fmt::join(EffectSet<lowfi::ScmEffects>::kNames, ", ")))
      ->check(scm_effect_name())
      ->capture_default_str();
  sub->add_option("--mu", a.run.friction, "ground friction relative to the tire data's")
      ->check(in_range(Range{0.01, 2, false, false}))
      ->capture_default_str();
  auto* inputs = sub->add_option("--inputs", a.inputs, "driver file: rows 'time steering throttle braking'");
  auto* maneuver = sub->add_option("--maneuver", a.maneuver, "built-in manoeuvre (JSON, docs/formats.md)");
  inputs->excludes(maneuver);
  sub->add_option("--end-time", a.run.end_time,
                  "simulated seconds (default: the driver file's last time or the manoeuvre's end_time)")
      ->check(in_range(Range{0, 1e5, true, false}));
  sub->add_option("--initial-speed", a.run.initial_speed, "initial forward speed [m/s]")
      ->check(in_range(Range{-50, 50, false, false}));
  sub->add_option("--step", a.run.max_step, "the integrator's largest step [s] (0: IDAS chooses)")
      ->check(in_range(Range{0, 0.1, false, false}))
      ->capture_default_str();
  sub->add_option("--rtol", a.run.rtol, "IDAS relative tolerance (absolute: rtol / 100; on SCM default 1e-3)")
      ->check(in_range(Range{1e-12, 1e-2, false, false}))
      ->capture_default_str();
  sub->add_option("--output-rate", a.run.output_rate, "rows per second in trajectory.csv and wheels.csv [Hz]")
      ->check(in_range(Range{0.1, 1e4, false, false}))
      ->capture_default_str();
  sub->add_flag("!--no-plots", a.plots, "skip trajectory.png");
  sub->add_flag("--vtu", a.vtu, "ParaView snapshots of the bodies: vtu/vehicle_NNNNN.vtu and vtu/vehicle.pvd");
  sub->add_option("--vtu-rate", a.run.vtu_rate, "snapshots per second with --vtu [Hz]")
      ->check(in_range(vehicle::kVehicleVtuRate))
      ->capture_default_str();
  sub->add_option("--out", a.out, "output folder")->required();
}
}  // namespace

Command add_vehicle(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "vehicle",
      "The full multibody vehicle (HMMWV template) on rigid ground or SCM soil; writes trajectory.csv and wheels.csv");
  auto a = std::make_shared<VehicleArgs>();
  add_options(sub, *a);
  return [a, sub] {
    const OutDir out = prepare_out_dir("--out", a->out);
    for (const char* key : {"--scm", "--scm-grid", "--scm-step", "--scm-effects"})
      if (a->terrain != "scm" && sub->count(key) > 0) throw InputError(fmt::format("{}: only with --terrain scm", key));
    if (a->terrain == "scm") {
      if (a->scm.empty()) throw InputError("--terrain scm: give the soil's parameter set with --scm FILE");
      if (sub->count("--mu") > 0) throw InputError("--mu: only with --terrain rigid (the soil sets the friction)");
      a->run.soil = lowfi::read_scm_json(a->scm);
      a->run.scm.effects = parse_scm_effects_option(a->scm_effects);
      lowfi::validate(a->run.scm, *a->run.soil);
      // The held soil wrench's error is of the soil step's order: a tighter integrator buys nothing
      // and costs 3-4x (docs/decisions.md).
      if (sub->count("--rtol") == 0) a->run.rtol = 1e-3;
    }
    if (sub->count("--vtu-rate") > 0 && !a->vtu) throw InputError("--vtu-rate: only with --vtu");
    if (a->inputs.empty() == a->maneuver.empty())
      throw InputError("terracal vehicle: give the driver as --inputs DRIVER.txt or --maneuver M.json (one of them)");
    const vehicle::FullVehicleSpec spec = vehicle::load_full_vehicle(a->vehicle);
    if (a->run.soil && !(spec.scm_wheel.width > 0))
      throw InputError(
          fmt::format("{}: wheel.width is not given: the wheels need it on SCM soil (--terrain scm)", a->vehicle));
    if (!spec.has_powertrain)
      spdlog::warn("{}: no powertrain: the wheels turn freely (no throttle, no brakes)", a->vehicle);
    const bool end_given = sub->count("--end-time") > 0;
    std::unique_ptr<DriverSeries> series;
    std::unique_ptr<Maneuver> maneuver;
    if (!a->inputs.empty()) {
      series = std::make_unique<DriverSeries>(DriverSeries::read(a->inputs));
      if (!end_given) a->run.end_time = series->end_time();
    } else {
      maneuver = std::make_unique<Maneuver>(Maneuver::read(a->maneuver, maneuver_vehicle(spec)));
      if (!end_given) a->run.end_time = maneuver->end_time();
      if (sub->count("--initial-speed") == 0) a->run.initial_speed = maneuver->initial_speed();
    }
    if (!(a->run.end_time > 0)) throw InputError(fmt::format("--end-time {}: must be positive", a->run.end_time));
    std::filesystem::create_directories(a->out);
    if (a->vtu) a->run.vtu_dir = a->out + "/vtu";
    spdlog::info("vehicle: {} on {}, {:.3g} s after {:.3g} s settling", a->vehicle,
                 a->run.soil ? fmt::format("SCM soil {} (grid {} m)", a->scm, a->run.scm.grid) : "rigid ground",
                 a->run.end_time, a->run.settle_time);
    const vehicle::VehicleRunResult r = vehicle::run_full_vehicle(spec, series.get(), maneuver.get(), a->run);
    write_vehicle_outputs(a->out, {a->vehicle, a->terrain, a->scm, a->inputs.empty() ? a->maneuver : a->inputs,
                                   !a->inputs.empty(), a->vtu},
                          a->run, r);
    if (a->plots) plot_trajectory(a->out, fmt::format("{} full vehicle (IDAS)", a->vehicle));
    fmt::print(
        "vehicle (full, IDAS): {:.3g} s simulated in {:.3g} s wall ({:.2g}x real time, settling included); "
        "written to {}/trajectory.csv\n",
        a->run.end_time, r.wall_seconds, a->run.end_time / std::max(r.wall_seconds, 1e-12), a->out);
    if (a->vtu) fmt::print("vehicle: {} snapshots in {}/vtu/vehicle.pvd\n", r.vtu_snapshots, a->out);
    return 0;
  };
}

}  // namespace terracal::app
