#include "apps/terrain_options.hpp"

#include <cmath>
#include <sstream>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/errors.hpp"
#include "core/json_file.hpp"
#include "highfi/crm_terrain.hpp"
#include "highfi/sph_engine.hpp"

namespace terracal::app {

void add_crm_settling_options(CLI::App* sub, TerrainOptions& o) {
  sub->add_option("--settle-time", o.settle_time, "CRM settling before the test [s]")->capture_default_str();
  sub->add_option("--settle-jitter", o.settle_jitter,
                  "CRM settling starts up to this fraction of the spacing off the lattice, seeded (0: the exact lattice; results/crm_settling)")
      ->capture_default_str();
  sub->add_option("--settle-seed", o.settle_seed, "the seed of --settle-jitter: another seed is another realisation of the same bed")
      ->capture_default_str();
  sub->add_option("--hourglass-damping", o.hourglass_damping,
                  "CRM effect hourglass_damping with this alpha: a Laplacian viscosity nu = alpha h c/10 that damps the lattice's "
                  "checkerboard mode; on for the rigs by default, because without it the bed softens with finer spacing and "
                  "larger bins (0: off; results/plate_bin_check)")
      ->capture_default_str();
  sub->add_option("--hourglass-stiffness", o.hourglass_stiffness,
                  "CRM effect hourglass_stiffness with this beta: a frictional spring k = beta E/(rho h^2) on each particle's "
                  "displacement that its neighbours' velocity gradient does not explain; on for the rigs by default, because the "
                  "damping alone lets soil escape from under a plate through the checkerboard mode (0: off, at most 0.1; "
                  "results/plate_bin_check)")
      ->capture_default_str();
  sub->add_option("--h-over-d0", o.h_over_d0,
                  "CRM smoothing length h over the particle spacing; 1.4 keeps the particle lattice stable under compression "
                  "(at 1.2 a column mode grows and softens the bed; results/crm_settling)")
      ->capture_default_str();
  sub->add_option("--marker-velocity", o.marker_velocity,
                  "CRM boundary markers' velocity: mirror (Adami's 2 v_wall - v~, v~ averaged around the marker), "
                  "mirror_image (2 v_wall - v at the marker's mirror image across the wall: a consistent mirror of a linear "
                  "flow), mirror_contact (Adami's mirror only where soil touches the wall: a held plate keeps more of its force, "
                  "but plate forces no longer converge with the spacing; "
                  "results/plate_bin_check, ninth study) or wall (the wall's own: plate curves nearly independent of the "
                  "plate's speed, but plate forces that no longer converge with the spacing; eighth study)")
      ->capture_default_str();
}

void add_terrain_options(CLI::App* sub, TerrainOptions& o, bool crm, bool scm) {
  if (crm) {
    sub->add_option("--soil", o.soil_json, "CRM soil material (JSON, DESIGN.md 'Soil')");
    sub->add_option("--spacing", o.spacing, "CRM particle spacing [m]")->capture_default_str();
    sub->add_option("--device", o.device, "CRM device: cpu, cuda or auto")->capture_default_str();
    sub->add_option("--cache", o.cache, "folder of settled CRM beds ('' = no cache)")->capture_default_str();
    add_crm_settling_options(sub, o);
    sub->add_option("--bin-scale", o.bin_scale, "CRM bin (and bed depth) scaled by this factor: the bin-size check")->capture_default_str();
    sub->add_option("--bin-depth-scale", o.bin_depth_scale, "CRM bed depth scaled by this factor instead (0: as --bin-scale)")->capture_default_str();
  }
  if (scm) {
    sub->add_option("--scm", o.scm_json, "SCM parameter file (Chrono SCM JSON or terracal's scm_params.json)");
    sub->add_option("--grid", o.grid, "SCM grid spacing [m]")->capture_default_str();
    sub->add_option("--scm-effects", o.scm_effects, "SCM effects: damping, elastic_unloading, bulldozing, or none")->capture_default_str();
    sub->add_option("--gravity", o.gravity, "gravity vector for SCM (default Earth) [m/s^2]")->expected(3);
  }
  sub->add_option("--step", o.step, "time step [s] (0: CRM from its CFL limit, SCM 1e-3)")->capture_default_str();
}

CrmSoil load_crm_soil(const std::string& path) { return parse_crm_soil(read_json_file(path, "soil file"), path); }

lowfi::ScmSoil load_scm_soil(const std::string& path) { return lowfi::read_scm_json(path); }

CrmDevice resolve_device(const std::string& device) {
  if (device == "cpu") return CrmDevice::kCpu;
  std::string why;
  const bool have = cuda_engine_available(&why);
  if (device == "cuda") {
    if (!have) throw InputError(fmt::format("--device cuda: no CUDA device available ({})", why));
    return CrmDevice::kCuda;
  }
  if (device != "auto") throw InputError(fmt::format("--device {}: expected cpu, cuda or auto", device));
  spdlog::info("CRM on the {}", have ? "GPU (CUDA)" : fmt::format("CPU ({})", why));
  return have ? CrmDevice::kCuda : CrmDevice::kCpu;
}

std::unique_ptr<TerrainSite> crm_site(const CrmSoil& soil, const TerrainOptions& o, double half_length, double half_width, double depth) {
  if (!(o.spacing > 0 && o.spacing < 1)) throw InputError(fmt::format("--spacing {}: expected in (0, 1) m", o.spacing));
  if (!(o.step >= 0)) throw InputError(fmt::format("--step {}: expected >= 0 s", o.step));
  if (!(o.settle_jitter >= 0 && o.settle_jitter <= 0.3))
    throw InputError(fmt::format("--settle-jitter {}: expected in [0, 0.3] (a fraction of the spacing)", o.settle_jitter));
  if (!(o.settle_seed >= 0 && o.settle_seed <= (1L << 62)))
    throw InputError(fmt::format("--settle-seed {}: expected an integer in [0, 2^62]", o.settle_seed));
  if (!(o.hourglass_damping >= 0 && o.hourglass_damping <= 2))
    throw InputError(fmt::format("--hourglass-damping {}: expected in [0, 2] (0: off)", o.hourglass_damping));
  if (!(o.hourglass_stiffness >= 0 && o.hourglass_stiffness <= 0.1))
    throw InputError(fmt::format("--hourglass-stiffness {}: expected in [0, 0.1] (0: off)", o.hourglass_stiffness));
  if (!(o.h_over_d0 >= 1.0 && o.h_over_d0 <= 1.6))
    throw InputError(fmt::format("--h-over-d0 {}: expected in [1.0, 1.6]", o.h_over_d0));
  if (o.marker_velocity != "mirror" && o.marker_velocity != "mirror_image" && o.marker_velocity != "mirror_contact" && o.marker_velocity != "wall")
    throw InputError(fmt::format("--marker-velocity {}: expected mirror, mirror_image, mirror_contact or wall", o.marker_velocity));
  if (!(o.bin_scale >= 1 && o.bin_scale <= 10)) throw InputError(fmt::format("--bin-scale {}: expected in [1, 10]", o.bin_scale));
  if (!(o.bin_depth_scale == 0 || (o.bin_depth_scale >= 1 && o.bin_depth_scale <= 10)))
    throw InputError(fmt::format("--bin-depth-scale {}: expected 0 (as --bin-scale) or in [1, 10]", o.bin_depth_scale));
  CrmScene sc;
  sc.source = o.soil_json.empty() ? "embedded soil" : o.soil_json;
  sc.soil = soil;
  sc.effects.artificial_viscosity = true;
  sc.effects.cohesion = soil.cohesion > 0;
  sc.effects.hourglass_damping = o.hourglass_damping > 0;
  if (o.hourglass_damping > 0) sc.numerics.hourglass_alpha = o.hourglass_damping;
  sc.effects.hourglass_stiffness = o.hourglass_stiffness > 0;
  if (o.hourglass_stiffness > 0) sc.numerics.hourglass_beta = o.hourglass_stiffness;
  sc.numerics.spacing = o.spacing;
  sc.numerics.h_over_d0 = o.h_over_d0;
  sc.numerics.marker_velocity = marker_velocity_from_name(o.marker_velocity);
  sc.numerics.time_step = o.step;
  // Whole spacings, and a bin at least a few spacings around the rig.
  const double d0 = o.spacing;
  sc.bin.size = {2 * std::ceil(half_length / d0) * d0, 2 * std::ceil(half_width / d0) * d0, std::ceil(1.5 * depth / d0) * d0};
  sc.bin.fill_height = std::ceil(depth / d0) * d0;
  sc.settle_time = o.settle_time;
  sc.settle_jitter = o.settle_jitter;
  sc.settle_seed = o.settle_seed;
  if (o.settle_jitter == 0 && o.settle_seed != kDefaultSettleSeed)
    spdlog::warn("--settle-seed {} has no effect without --settle-jitter: the bed settles from the exact lattice", o.settle_seed);
  spdlog::info("CRM bin {:.3g} x {:.3g} m, soil {:.3g} m deep at spacing {} m: settling (or reading the cached bed)", sc.bin.size.x,
               sc.bin.size.y, sc.bin.fill_height, d0);
  return std::make_unique<CrmSite>(sc, resolve_device(o.device), o.cache);
}

std::unique_ptr<TerrainSite> scm_site(const lowfi::ScmSoil& soil, const TerrainOptions& o, const Vec3<double>& gravity) {
  lowfi::ScmSettings s;
  s.grid = o.grid;
  s.time_step = o.step > 0 ? o.step : 1e-3;
  s.gravity = gravity;
  if (o.gravity.size() == 3) s.gravity = {o.gravity[0], o.gravity[1], o.gravity[2]};
  std::vector<std::string> effects;
  for (const auto& e : o.scm_effects)
    if (!e.empty() && e != "none") effects.push_back(e);
  s.effects = lowfi::parse_scm_effects(effects, "--scm-effects");
  return std::make_unique<lowfi::ScmSite>(soil, s);
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
      throw InputError(fmt::format("{} '{}': '{}' is not a number (expected a comma-separated list such as 0,0.2,0.4)", option, text, item));
    }
  }
  if (out.empty()) throw InputError(fmt::format("{} '{}': empty list", option, text));
  return out;
}

}  // namespace terracal::app
