// `terracal wheel-table`: the SCM single-wheel rig over loads x slips (x slip angles), in parallel;
// writes the table (HDF5) that the ROMs' deformable_terrain effect drives on.
#include <chrono>
#include <filesystem>
#include <memory>

#include <fmt/format.h>

#include "apps/cli_checks.hpp"
#include "apps/commands.hpp"
#include "apps/soil_choice.hpp"
#include "apps/terrain_options.hpp"
#include "apps/wheel_table.hpp"
#include "core/errors.hpp"

namespace terracal::app {

namespace {
struct WheelTableArgs {
  std::string wheel, loads, slips = kDefaultSlips, angles = "0", out;
  double duration = 4.0, average_from = 0.5;
  TerrainOptions options;
};
}  // namespace

Command add_wheel_table(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "wheel-table", "SCM single-wheel runs over loads x slips (x slip angles); writes the ROMs' terrain table (HDF5)");
  auto a = std::make_shared<WheelTableArgs>();
  sub->add_option("--wheel", a->wheel, "wheel file (JSON, docs/formats.md 'Wheel'; its mass is replaced by each load)")
      ->required();
  sub->add_option("--loads", a->loads, "vertical loads on the wheel [N], comma-separated, increasing")
      ->required()
      ->check(list_in_range(Range{0, 1e7, true, false, "N"}));
  sub->add_option("--slips", a->slips, "longitudinal slips, comma-separated, increasing (negative: skid)")
      ->check(list_in_range(rigs::WheelRanges::kSlip))
      ->capture_default_str();
  sub->add_option("--slip-angles", a->angles, "slip angles [rad], comma-separated, increasing from 0")
      ->check(list_in_range(rigs::WheelRanges::kSlipAngle))
      ->capture_default_str();
  sub->add_option("--duration", a->duration, "simulated seconds per run")
      ->check(in_range(rigs::WheelRanges::kDuration))
      ->capture_default_str();
  sub->add_option("--average-from", a->average_from, "steady means over t >= this fraction of the run")
      ->check(in_range(rigs::WheelRanges::kAverageFrom))
      ->capture_default_str();
  sub->add_option("--out", a->out, "the table (HDF5 file, docs/formats.md 'Wheel table')")->required();
  add_terrain_options(sub, a->options, false, true);
  return [a] {
    if (std::filesystem::is_directory(a->out))
      throw InputError(fmt::format("--out '{}': is a folder; give the table's file name (T.h5)", a->out));
    if (a->options.scm_json.empty()) throw InputError("wheel-table needs --scm SCM.json (an SCM parameter set)");
    const rigs::WheelSpec wheel = rigs::read_wheel_json(a->wheel);
    WheelTablePlan plan;
    plan.loads = parse_list(a->loads, "--loads");
    plan.slips = parse_list(a->slips, "--slips");
    plan.angles = parse_list(a->angles, "--slip-angles");
    plan.run.duration = a->duration;
    plan.run.average_from = a->average_from;
    const SoilChoice soil = choose_soil(SoilModel::kScm, a->options);
    check_wheel_table(soil, a->options, wheel, plan);
    const auto parent = std::filesystem::path(a->out).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent);
    const auto start = std::chrono::steady_clock::now();
    rom::TerrainTable t = run_wheel_table(soil, a->options, wheel, plan);
    t.soil = a->options.scm_json;
    t.wheel = a->wheel;
    rom::write_terrain_table(a->out, t);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    fmt::print("wheel-table: {} loads x {} slips x {} slip angles ({} runs) in {:.3g} s wall; written to {}\n",
               t.load.size(), t.slip.size(), t.angle.size(), t.dbp.size(), wall, a->out);
    return 0;
  };
}

}  // namespace terracal::app
