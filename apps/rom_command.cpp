// `terracal rom`: one reduced-order vehicle (11 or 18 DOF) driven by a driver file or a built-in
// manoeuvre; writes trajectory.csv, trajectory.png and run.json, and with a driver file inputs.txt
// (its rows: the inputs applied).
#include <algorithm>
#include <filesystem>
#include <memory>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "apps/cli_checks.hpp"
#include "apps/commands.hpp"
#include "apps/memory_check.hpp"
#include "apps/out_dir.hpp"
#include "apps/report_plots.hpp"
#include "apps/rom_choices.hpp"
#include "core/atomic_file.hpp"
#include "core/device_selftest.hpp"
#include "core/errors.hpp"
#include "rom/batch_h5.hpp"
#include "rom/batch_vary.hpp"
#include "rom/rom_batch.hpp"
#include "rom/rom_run.hpp"
#include "rom/rom_vehicle_json.hpp"
#include "rom/terrain_table_h5.hpp"
#include "rom/trajectory_csv.hpp"

namespace terracal::app {

namespace {
struct RomArgs {
  rom::RomRunOptions run;
  std::string vehicle, tire, maneuver, out;
  std::vector<std::string> inputs;
  double friction = 1.0, gravity = 9.81;
  bool plots = true;
  long batch = 0;
  std::string vary, device = "auto", channels, terrain_table;
  std::uint64_t seed = 1;
};

const std::map<std::string, rom::RomIntegrator> kIntegrators = {{"cvodes", rom::RomIntegrator::kCvodes},
                                                                {"half-implicit", rom::RomIntegrator::kHalfImplicit}};
}  // namespace

namespace {
std::vector<rom::BatchChannel> parse_channels(const std::string& list) {
  std::vector<rom::BatchChannel> out;
  if (list.empty()) return out;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t end = std::min(list.find(',', start), list.size());
    const std::string name = list.substr(start, end - start);
    int found = -1;
    for (int c = 0; c < rom::kBatchChannelCount; ++c)
      if (name == rom::kBatchChannelNames[c]) found = c;
    if (found < 0)
      throw InputError(
          fmt::format("--channels: '{}' is not a channel; expected x, y, yaw, vx, vy, yaw_rate, ax, ay, roll", name));
    for (auto c : out)
      if (c == found) throw InputError(fmt::format("--channels: '{}' is listed twice", name));
    out.push_back(static_cast<rom::BatchChannel>(found));
    start = end + 1;
  }
  return out;
}

int run_batch(const RomArgs& a, const rom::RomVehicle& vehicle, const rom::RomRunOptions& run,
              const std::vector<DriverSeries>& series) {
  rom::BatchOptions o;
  o.model = run.model;
  o.step = run.step;
  o.end_time = run.end_time;
  o.initial_speed = run.initial_speed;
  o.channels = parse_channels(a.channels);
  o.output_rate = o.channels.empty() ? 0.0 : run.output_rate;
  o.device = batch_device(a.device);
  // Host memory: every vehicle's summary, final state and channel samples (the GPU runs them in
  // chunks), and with --vary its own parameter set.
  const double samples = o.output_rate > 0 ? std::floor(run.end_time * o.output_rate + 0.5) + 1 : 0;
  const double per_vehicle = 8.0 * (rom::kBatchMetricCount + 33 + o.channels.size() * samples) +
                             (a.vary.empty() ? 0.0 : sizeof(rom::RomVehicle));
  check_memory("--batch " + std::to_string(a.batch), "the batch's outputs", per_vehicle * a.batch, 0.0,
               "fewer vehicles, channels or a lower --output-rate", true);
  std::unique_ptr<rom::VaryDraws> draws;
  std::vector<rom::RomVehicle> vehicles{vehicle};
  if (!a.vary.empty()) {
    draws = std::make_unique<rom::VaryDraws>(rom::draw_vehicles(vehicle, rom::read_vary(a.vary), a.batch, a.seed));
    vehicles = std::move(draws->vehicles);
  }
  std::filesystem::create_directories(a.out);
  std::vector<const DriverSeries*> drivers;
  if (series.size() == 1) {
    drivers.push_back(&series.front());
  } else {
    for (long i = 0; i < a.batch; ++i) drivers.push_back(&series[i % series.size()]);
  }
  const rom::BatchResult r = rom::run_rom_batch(vehicles, drivers, a.batch, o);
  rom::BatchH5Info info;
  info.vehicle = a.vehicle;
  info.seed = a.seed;
  rom::write_batch_h5(a.out + "/batch.h5", r, o, draws.get(), info);
  if (r.failed > 0)
    spdlog::warn(
        "rom batch: {} of {} vehicles diverged (summary/failed_at >= 0 in batch.h5): --step {} s is too large for them",
        r.failed, r.vehicles, o.step);
  fmt::print(
      "rom batch ({}, {}): {} vehicles x {:.3g} s in {:.3g} s wall ({:.3g} vehicle-seconds per second); written to "
      "{}/batch.h5\n",
      rom::model_name(o.model), r.device, r.vehicles, o.end_time, r.wall_seconds,
      r.vehicles * o.end_time / std::max(r.wall_seconds, 1e-12), a.out);
  return 0;
}
// One vehicle: trajectory.csv, run.json, trajectory.png and inputs.txt.
int run_single(const RomArgs& a, const rom::RomVehicle& vehicle, const rom::RomRunOptions& run,
               rom::RomDriver& driver) {
  std::filesystem::create_directories(a.out);
  const rom::RomRunResult r = rom::run_rom(vehicle, driver, run);
  rom::write_trajectory_csv(a.out + "/trajectory.csv", r.samples);
  if (driver.series) {  // the inputs applied, as a driver file: the series' rows (read back exactly)
    std::string source = driver.series->source();
    std::replace_if(
        source.begin(), source.end(), [](char c) { return c == '\n' || c == '\r'; }, '?');
    std::string d =
        fmt::format("# driver inputs of terracal rom: the rows of {}\n# time steering throttle braking\n", source);
    const DriverSeries& s = *driver.series;
    for (std::size_t i = 0; i < s.times().size(); ++i)
      d += fmt::format("{:.17g} {:.17g} {:.17g} {:.17g}\n", s.times()[i], s.steering()[i], s.throttle()[i],
                       s.braking()[i]);
    write_text_atomically(a.out + "/inputs.txt", d);
  } else {  // a manoeuvre's held inputs as steps: a row at each control time and 1 us before the next
    std::string d =
        "# driver inputs of terracal rom --maneuver: held from each control time, as steps 1e-6 s wide\n"
        "# time steering throttle braking\n";
    const auto row = [&](double t, const DriverInput& in) {
      d += fmt::format("{:.17g} {:.17g} {:.17g} {:.17g}\n", t, in.steering, in.throttle, in.braking);
    };
    const auto& h = r.held_inputs;
    for (std::size_t i = 0; i < h.size(); ++i) {
      row(h[i].first, h[i].second);
      const double next = i + 1 < h.size() ? h[i + 1].first : run.end_time;
      if (next - 1e-6 > h[i].first) row(next - (i + 1 < h.size() ? 1e-6 : 0.0), h[i].second);
    }
    write_text_atomically(a.out + "/inputs.txt", d);
  }
  nlohmann::json j = {{"model", rom::model_name(run.model)},
                            {"integrator", rom::integrator_name(run.integrator)},
                            {"vehicle", a.vehicle},
                            {"end_time", run.end_time},
                            {"steps", r.steps},
                            {"rhs_evaluations", r.rhs_evaluations},
                            {"wall_seconds", r.wall_seconds},
                            {"real_time_factor", run.end_time / std::max(r.wall_seconds, 1e-12)}};
  if (!a.terrain_table.empty()) j["terrain_table"] = a.terrain_table;
  write_text_atomically(a.out + "/run.json", j.dump(2) + "\n");
  if (a.plots)
    plot_trajectory(
        a.out, fmt::format("{} {} ({})", a.vehicle, rom::model_name(run.model), rom::integrator_name(run.integrator)));
  fmt::print("rom ({}, {}): {:.3g} s simulated in {:.3g} s wall ({:.0f}x real time); written to {}/trajectory.csv\n",
             rom::model_name(run.model), rom::integrator_name(run.integrator), run.end_time, r.wall_seconds,
             run.end_time / std::max(r.wall_seconds, 1e-12), a.out);
  return 0;
}

void add_rom_options(CLI::App* sub, RomArgs& a) {
  add_choice(sub, "--model", a.run.model, kRomModels, "vehicle model")->required()->default_str("");
  sub->add_option("--vehicle", a.vehicle, "vehicle file (JSON, ours or LFDM's) or preset: hmmwv, sedan")->required();
  sub->add_option("--tire", a.tire, "TMeasy tire file replacing the vehicle's (needed with an LFDM vehicle file)");
  auto* inputs = sub->add_option("--inputs", a.inputs,
                                 "driver file: rows 'time steering throttle braking' (with --batch: several files, "
                                 "vehicle i driven by file i mod their number)");
  auto* maneuver = sub->add_option("--maneuver", a.maneuver, "built-in manoeuvre (JSON, docs/formats.md)");
  inputs->excludes(maneuver);
  sub->add_option("--end-time", a.run.end_time,
                  "simulated seconds (default: the driver file's last time or the "
                  "manoeuvre's end_time)")
      ->check(in_range(Range{0, 1e5, true, false}));
  sub->add_option("--initial-speed", a.run.initial_speed, "initial forward speed [m/s] (negative: backwards)")
      ->check(in_range(Range{-100, 100, false, false}));
  add_choice(sub, "--integrator", a.run.integrator, kIntegrators, "time integrator");
  sub->add_option("--step", a.run.step, "fixed step of the half-implicit scheme [s]")
      ->check(in_range(Range{1e-6, 0.1, false, false}))
      ->capture_default_str();
  sub->add_option("--rtol", a.run.rtol, "CVODES relative tolerance")
      ->check(in_range(Range{1e-12, 1e-1, false, false}))
      ->capture_default_str();
  sub->add_option("--atol", a.run.atol, "CVODES absolute tolerance")
      ->check(in_range(Range{1e-14, 1e-1, false, false}))
      ->capture_default_str();
  sub->add_option("--output-rate", a.run.output_rate, "samples per second in trajectory.csv [Hz]")
      ->check(in_range(Range{0.1, 1e4, false, false}))
      ->capture_default_str();
  sub->add_option("--friction", a.friction, "road friction relative to the tire data's")
      ->check(in_range(Range{0.01, 2, false, false}))
      ->capture_default_str();
  sub->add_option("--gravity", a.gravity, "gravitational acceleration [m/s^2] (Moon: 1.62)")
      ->check(in_range(Range{0.1, 30, false, false}))
      ->capture_default_str();
  sub->add_flag("!--no-plots", a.plots, "skip trajectory.png");
  sub->add_option("--batch", a.batch, "N vehicles in one batch (half-implicit); writes batch.h5")
      ->check(whole_in(1, 10000000));
  sub->add_option("--vary", a.vary, "per-parameter distributions of the batch (JSON)");
  add_seed_option(sub, a.seed, "seed of the --vary draws");
  sub->add_option("--device", a.device, "batch on cpu, cuda or auto")
      ->check(CLI::IsMember({"cpu", "cuda", "auto"}))
      ->capture_default_str();
  sub->add_option("--channels", a.channels,
                  "batch channels sampled at --output-rate: x,y,yaw,vx,vy,yaw_rate,ax,ay,roll");
  sub->add_option("--terrain-table", a.terrain_table,
                  "soft soil: tire forces from this wheel table (terracal wheel-table; effect deformable_terrain)");
  sub->add_option("--out", a.out, "output folder")->required();
}

}  // namespace

Command add_rom(CLI::App& app) {
  auto* sub =
      app.add_subcommand("rom", "A reduced-order vehicle (11, 18 or 24 DOF) on rigid ground or a wheel table's soil; writes trajectory.csv");
  auto a = std::make_shared<RomArgs>();
  add_rom_options(sub, *a);
  return [a, sub] {
    if (a->batch > 0) {
      if (!a->maneuver.empty())
        throw InputError(
            "--maneuver: a batch runs driver files (--inputs); the manoeuvres' controllers run one vehicle at a time");
      if (sub->count("--integrator") > 0 && a->run.integrator != rom::RomIntegrator::kHalfImplicit)
        throw InputError("--integrator cvodes: a batch steps with the half-implicit scheme only");
    }
    const OutDir out = prepare_out_dir("--out", a->out);
    if (a->inputs.empty() == a->maneuver.empty())
      throw InputError("terracal rom: give the driver as --inputs DRIVER.txt or --maneuver M.json (one of them)");
    rom::RomVehicle vehicle = rom::load_rom_vehicle(a->vehicle, a->tire);
    if (!a->terrain_table.empty()) rom::attach_terrain_table(vehicle, a->terrain_table);
    vehicle.friction = a->friction;
    vehicle.gravity = a->gravity;
    rom::validate(vehicle, a->vehicle);
    rom::RomRunOptions run = a->run;
    const bool end_given = sub->count("--end-time") > 0;
    std::vector<DriverSeries> series;
    std::unique_ptr<Maneuver> maneuver;
    rom::RomDriver driver;
    if (!a->inputs.empty()) {
      if (a->inputs.size() > 1 && a->batch == 0)
        throw InputError(fmt::format("--inputs: {} driver files for one vehicle; several files are for --batch N",
                                     a->inputs.size()));
      for (const std::string& path : a->inputs) series.push_back(DriverSeries::read(path));
      driver.series = &series.front();
      if (!end_given) {  // the longest file's; the others hold their last row
        run.end_time = 0;
        for (const DriverSeries& s : series) run.end_time = std::max(run.end_time, s.end_time());
      }
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
    if (a->batch > 0) return run_batch(*a, vehicle, run, series);
    for (const char* o : {"--vary", "--device", "--channels", "--seed"})
      if (sub->count(o) > 0) throw InputError(fmt::format("{}: only with --batch N", o));
    return run_single(*a, vehicle, run, driver);
  };
}

}  // namespace terracal::app
