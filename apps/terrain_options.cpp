#include "apps/terrain_options.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "apps/cli_checks.hpp"
#include "core/errors.hpp"
#include "core/json_file.hpp"
#include "highfi/crm/crm_terrain.hpp"
#include "highfi/crm/sph_engine.hpp"

namespace terracal::app {

namespace {
std::map<std::string, MarkerVelocity> marker_velocity_map() {
  std::map<std::string, MarkerVelocity> m;
  for (const char* name : kMarkerVelocityNames) m[name] = marker_velocity_from_name(name);
  return m;
}
// Notes the option's name in `given` when the command line gives it.
CLI::Option* noted(CLI::Option* opt, std::vector<std::string>& given) {
  const std::string name = opt->get_name();
  opt->each([&given, name](const std::string&) {
    if (std::find(given.begin(), given.end(), name) == given.end()) given.push_back(name);
  });
  return opt;
}
}  // namespace

void add_device_option(CLI::App* sub, DeviceChoice& device) {
  const std::map<std::string, DeviceChoice> names{
      {"cpu", DeviceChoice::kCpu}, {"cuda", DeviceChoice::kCuda}, {"auto", DeviceChoice::kAuto}};
  add_choice(sub, "--device", device, names, "CRM device: cpu, cuda or auto (cuda when a device is present)");
}

void add_crm_settling_options(CLI::App* sub, TerrainOptions& o) {
  sub->add_option("--settle-time", o.settle_time, "CRM settling before the test [s]")
      ->check(in_range(CrmRanges::kSettleTime))
      ->capture_default_str();
  sub->add_option("--settle-jitter", o.settle_jitter,
                  "CRM settling starts up to this fraction of the spacing off the lattice (0: the exact lattice)")
      ->check(in_range(CrmRanges::kSettleJitter))
      ->capture_default_str();
  sub->add_option("--settle-seed", o.settle_seed,
                  "seed of --settle-jitter: another seed, another realisation of the bed")
      ->transform(whole_in(0, CrmRanges::kMaxSettleSeed))
      ->capture_default_str();
  const auto damping = HourglassDamping::settings()[0];
  sub->add_option("--hourglass-damping", o.hourglass_damping,
                  fmt::format("CRM effect hourglass_damping with this alpha ({}; 0: off)", damping.help))
      ->check(off_or_in_range(damping.range))
      ->capture_default_str();
  const auto stiffness = HourglassStiffness::settings()[0];
  sub->add_option("--hourglass-stiffness", o.hourglass_stiffness,
                  fmt::format("CRM effect hourglass_stiffness with this beta ({}; 0: off)", stiffness.help))
      ->check(off_or_in_range(stiffness.range))
      ->capture_default_str();
  sub->add_option("--h-over-d0", o.h_over_d0, "CRM smoothing length over the particle spacing")
      ->check(in_range(CrmRanges::kHOverD0))
      ->capture_default_str();
  add_choice(sub, "--marker-velocity", o.marker_velocity, marker_velocity_map(),
             "CRM boundary markers' velocity (docs/crm_scene.md)");
}

CLI::Option* add_crm_terrain_options(CLI::App* sub, TerrainOptions& o) {
  auto* soil = sub->add_option("--soil", o.soil_json, "CRM soil material (JSON, docs/formats.md 'CRM soil')");
  sub->add_option("--spacing", o.spacing, "CRM particle spacing [m]")
      ->check(in_range(RigRanges::kSpacing))
      ->capture_default_str();
  add_device_option(sub, o.device);
  sub->add_option("--concurrent-runs", o.concurrent_runs,
                  fmt::format("CRM runs of a sweep at once (0: on a GPU up to {} that fit, on the CPU 1)", kAutoRunsAtOnce))
      ->check(in_range(RigRanges::kConcurrentRuns))
      ->capture_default_str();
  sub->add_option("--cache", o.cache, "folder of settled CRM beds ('' = no cache)")->capture_default_str();
  add_crm_settling_options(sub, o);
  sub->add_option("--bin-scale", o.bin_scale, "CRM bins (and bed depth) scaled by this factor: the bin-size check")
      ->check(in_range(RigRanges::kBinScale))
      ->capture_default_str();
  sub->add_option("--bin-depth-scale", o.bin_depth_scale,
                  "CRM bed depth scaled by this factor instead (0: as --bin-scale)")
      ->check(off_or_in_range(RigRanges::kBinScale))
      ->capture_default_str();
  return soil;
}

void add_scm_grid_option(CLI::App* sub, TerrainOptions& o) {
  sub->add_option("--grid", o.grid, "SCM grid spacing [m]")
      ->check(in_range(RigRanges::kScmGrid))
      ->capture_default_str();
}

void add_step_option(CLI::App* sub, TerrainOptions& o) {
  sub->add_option("--step", o.step, "time step [s] (0: CRM from its CFL limit, SCM 1e-3 s)")
      ->check(in_range(RigRanges::kStep))
      ->capture_default_str();
}

void add_terrain_options(CLI::App* sub, TerrainOptions& o, bool crm, bool scm) {
  if (crm) {
    const auto soil = add_crm_terrain_options(sub, o);
    // Every CRM knob but --soil (choose_soil names a soil file given to the wrong solver itself).
    const auto options = sub->get_options();
    for (auto it = std::find(options.begin(), options.end(), soil) + 1; it != options.end(); ++it)
      noted(*it, o.crm_given);
  }
  if (scm) {
    sub->add_option("--scm", o.scm_json, "SCM parameter file (Chrono SCM JSON or terracal's scm_params.json)");
    add_scm_grid_option(sub, o);
    noted(sub->get_option("--grid"), o.scm_given);
    noted(
        sub->add_option("--scm-effects", o.scm_effects,
                        fmt::format("SCM effects: {}, or none", fmt::join(EffectSet<lowfi::ScmEffects>::kNames, ", ")))
            ->check(scm_effect_name())
            ->capture_default_str(),
        o.scm_given);
    sub->add_option("--gravity", o.gravity, "gravity vector for SCM (default Earth) [m/s^2]")->expected(3);
  }
  add_step_option(sub, o);
}

CrmSoil load_crm_soil(const std::string& path) { return parse_crm_soil(read_json_file(path, "soil file"), path); }

lowfi::ScmSoil load_scm_soil(const std::string& path) { return lowfi::read_scm_json(path); }

CrmDevice crm_device(DeviceChoice device) {
  if (device == DeviceChoice::kCpu) return CrmDevice::kCpu;
  std::string why;
  const bool have = cuda_engine_available(&why);
  if (device == DeviceChoice::kCuda && !have)
    throw InputError(fmt::format("--device cuda: no CUDA device available ({})", why));
  return have ? CrmDevice::kCuda : CrmDevice::kCpu;
}

CrmDevice resolve_device(DeviceChoice device) {
  const CrmDevice d = crm_device(device);
  if (device != DeviceChoice::kAuto) return d;
  std::string why;
  cuda_engine_available(&why);
  spdlog::info("CRM on the {}", d == CrmDevice::kCuda ? "GPU (CUDA)" : fmt::format("CPU ({})", why));
  return d;
}

// The rigs' CRM scene: the soil, the rigs' effects and the resolution from the options. Every value
// is checked by validate_crm_scene (CrmSite), against the ranges the command line checked too.
CrmScene crm_site_scene(const CrmSoil& soil, const TerrainOptions& o, double half_length, double half_width,
                        double depth) {
  check_range(RigRanges::kSpacing, o.spacing, "--spacing");
  check_range(RigRanges::kBinScale, o.bin_scale, "--bin-scale");
  check_range(RigRanges::kStep, o.step, "--step");
  CrmScene sc;
  sc.source = o.soil_json.empty() ? "embedded soil" : o.soil_json;
  sc.soil = soil;
  sc.effects.enable<ArtificialViscosity>();
  if (soil.cohesion > 0) sc.effects.enable<Cohesion>();
  if (o.hourglass_damping > 0) sc.effects.enable<HourglassDamping>({o.hourglass_damping});
  if (o.hourglass_stiffness > 0) sc.effects.enable<HourglassStiffness>({o.hourglass_stiffness});
  sc.numerics.spacing = o.spacing;
  sc.numerics.h_over_d0 = o.h_over_d0;
  sc.numerics.marker_velocity = o.marker_velocity;
  sc.numerics.time_step = o.step;
  // Whole spacings, and a bin at least a few spacings around the rig.
  const double d0 = o.spacing;
  sc.bin.size = {2 * std::ceil(half_length / d0) * d0, 2 * std::ceil(half_width / d0) * d0,
                 std::ceil(1.5 * depth / d0) * d0};
  sc.bin.fill_height = std::ceil(depth / d0) * d0;
  sc.settle_time = o.settle_time;
  sc.settle_jitter = o.settle_jitter;
  sc.settle_seed = o.settle_seed;
  return sc;
}

std::unique_ptr<TerrainSite> crm_site(const CrmSoil& soil, const TerrainOptions& o, double half_length,
                                      double half_width, double depth) {
  const CrmScene sc = crm_site_scene(soil, o, half_length, half_width, depth);
  const double d0 = o.spacing;
  if (o.settle_jitter == 0 && o.settle_seed != kDefaultSettleSeed)
    spdlog::warn("--settle-seed {} has no effect without --settle-jitter: the bed settles from the exact lattice",
                 o.settle_seed);
  spdlog::info("CRM bin {:.3g} x {:.3g} m, soil {:.3g} m deep at spacing {} m: settling (or reading the cached bed)",
               sc.bin.size.x, sc.bin.size.y, sc.bin.fill_height, d0);
  return std::make_unique<CrmSite>(sc, resolve_device(o.device), o.cache);
}

std::unique_ptr<TerrainSite> scm_site(const lowfi::ScmSoil& soil, const TerrainOptions& o,
                                      const Vec3<double>& gravity) {
  check_range(RigRanges::kScmGrid, o.grid, "--grid");
  check_range(RigRanges::kStep, o.step, "--step");
  lowfi::ScmSettings s;
  s.grid = o.grid;
  s.time_step = o.step > 0 ? o.step : 1e-3;
  s.gravity = gravity;
  if (o.gravity.size() == 3) s.gravity = {o.gravity[0], o.gravity[1], o.gravity[2]};
  s.effects = parse_scm_effects_option(o.scm_effects);
  return std::make_unique<lowfi::ScmSite>(soil, s);
}

CLI::Validator scm_effect_name() {
  return CLI::Validator(
      [](std::string& name) -> std::string {
        try {
          parse_scm_effects_option({name});
        } catch (const InputError& e) {
          const std::string m = e.what(), prefix = "--scm-effects: ";  // CLI11 names the option itself
          return m.rfind(prefix, 0) == 0 ? m.substr(prefix.size()) : m;
        }
        return {};
      },
      "EFFECT");
}

lowfi::ScmEffectChoice parse_scm_effects_option(const std::vector<std::string>& list) {
  std::vector<std::string> effects;
  for (const auto& e : list)
    if (!e.empty() && e != "none") effects.push_back(e);
  return lowfi::parse_scm_effects(effects, "--scm-effects");
}

std::vector<double> parse_list(const std::string& text, const std::string& option) {
  std::vector<double> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    try {
      std::size_t used = 0;
      const double v = std::stod(item, &used);
      if (used != item.size() || !std::isfinite(v)) throw std::invalid_argument(item);
      out.push_back(v);
    } catch (const std::exception&) {
      throw InputError(fmt::format("{} '{}': '{}' is not a number (expected a comma-separated list such as 0,0.2,0.4)",
                                   option, text, item));
    }
  }
  if (out.empty()) throw InputError(fmt::format("{} '{}': empty list", option, text));
  return out;
}

}  // namespace terracal::app
