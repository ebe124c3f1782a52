// The checks of a CRM scene, whether read from JSON or built in code (the rigs, tests): every rule
// of docs/crm_scene.md, before any particle exists. Also resolves what the scene leaves open: the
// bin's size on whole spacings and the time step from the CFL limit.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/errors.hpp"
#include "highfi/crm/crm_scene.hpp"
#include "highfi/crm/lattice_stability.hpp"

namespace terracal {

namespace {

// Refuses the scene: "<source>: key 'KEY': WHAT".
struct SceneFail {
  const std::string& source;
  [[noreturn]] void operator()(const std::string& key, const std::string& what) const {
    throw InputError(fmt::format("{}: key '{}': {}", source, key, what));
  }
};

void check_soil(const CrmSoil& soil, const SceneFail& fail) {
  if (!(soil.density > 0)) fail("soil.density", fmt::format("value {} must be > 0", soil.density));
  if (!(soil.young_modulus > 0)) fail("soil.young_modulus", fmt::format("value {} must be > 0", soil.young_modulus));
  if (!(soil.poisson_ratio >= 0 && soil.poisson_ratio < 0.5))
    fail("soil.poisson_ratio", fmt::format("value {} is outside [0, 0.5)", soil.poisson_ratio));
}

// Each named effect's settings against their ranges, and each effect's rules for the scene.
void check_effects(const CrmScene& sc, const SceneFail& fail) {
  check_effect_settings(sc.effects, sc.source);
  for_each_effect(CrmEffects{}, [&](auto tag) {
    using E = typename decltype(tag)::type;
    E::check_scene(sc, sc.effects.on<E>(), fail);
  });
}

void check_settling(const CrmScene& sc) {
  check_range(CrmRanges::kSettleTime, sc.settle_time, "settle_time", sc.source);
  check_range(CrmRanges::kSettleJitter, sc.settle_jitter, "settle_jitter", sc.source);
  if (sc.settle_seed < 0 || sc.settle_seed > CrmRanges::kMaxSettleSeed)
    SceneFail{sc.source}("settle_seed", fmt::format("value {} is outside [0, 2^62]", sc.settle_seed));
}

// The lattice the bed starts from must be stable under its own weight, or a mode the velocity
// gradient does not see grows from round-off and softens the bed (lattice_stability.hpp). A
// warning, not an error: studies run the unstable settings on purpose.
void warn_unstable_lattice(const CrmScene& sc) {
  const CrmSoil& soil = sc.soil;
  const CrmNumerics& n = sc.numerics;
  const double szz = -soil.density * std::sqrt(dot(soil.gravity, soil.gravity)) * sc.bin.fill_height;
  const double k0 = soil.poisson_ratio / (1 - soil.poisson_ratio);
  const double lambda = soil.bulk_modulus() - 2 * soil.shear_modulus() / 3;
  const LatticeStability ls = lattice_stability(n.kernel, n.h_over_d0, n.spacing, soil.density, lambda,
                                                soil.shear_modulus(), {k0 * szz, k0 * szz, szz});
  if (ls.growth_rate > 1)
    spdlog::warn(
        "{}: resolution.h_over_d0 {} with the {} kernel: the particle lattice is unstable under the bed's weight "
        "(a mode at k d0/pi = ({:.2g}, {:.2g}, {:.2g}) grows at {:.3g} 1/s at its floor, unseen by the velocity "
        "gradient; results/crm_settling). h/d0 = 1.4 with wendland_c2 keeps it stable.",
        sc.source, n.h_over_d0, n.kernel == KernelType::kWendlandC2 ? "wendland_c2" : "cubic_spline", ls.wave[0],
        ls.wave[1], ls.wave[2], ls.growth_rate);
}

// The bin's walls sit on the particle lattice: its length and width become whole numbers of spacings.
void fit_bin(CrmScene& sc, const SceneFail& fail) {
  const double d0 = sc.numerics.spacing;
  for (int q = 0; q < 2; ++q) sc.bin.size[q] = std::max(1.0, double(std::lround(sc.bin.size[q] / d0))) * d0;
  const CrmBin& bin = sc.bin;
  const double minimum_cells = 4;
  const char* axis[3] = {"x", "y", "z"};
  for (int q = 0; q < 2; ++q)
    if (bin.size[q] < minimum_cells * d0)
      fail("bin.size", fmt::format("{} = {} m is less than {} particle spacings ({} m): spacing too coarse for the bin",
                                   axis[q], bin.size[q], minimum_cells, minimum_cells * d0));
  if (bin.fill_height < 3 * d0)
    fail("bin.fill_height",
         fmt::format("value {} m is less than 3 spacings ({} m): spacing too coarse", bin.fill_height, 3 * d0));
  if (bin.fill_height > bin.size.z)
    fail("bin.fill_height", fmt::format("value {} m is above the wall height {} m", bin.fill_height, bin.size.z));
  if (bin.fill_length > bin.size.x + 1e-12)
    fail("bin.fill_length", fmt::format("value {} m is longer than the bin ({} m)", bin.fill_length, bin.size.x));
  if (bin.fill_length > 0 && bin.fill_length < 2 * d0)
    fail("bin.fill_length", fmt::format("value {} m is less than 2 spacings", bin.fill_length));
}

// A body's shape must span enough spacings to carry boundary markers that hold the soil back.
void check_body_resolution(const CrmBody& body, const std::string& key, double d0, const SceneFail& fail) {
  const BodyShape& s = body.shape;
  auto too_coarse = [&](const char* dim, double value, double need) {
    if (value < need * d0)
      fail(key + ".shape." + dim,
           fmt::format("value {} m is less than {} particle spacings ({} m): spacing too coarse for the body", value,
                       need, need * d0));
  };
  switch (s.type) {
    case ShapeType::kBox:
      too_coarse("size", 2 * std::min({s.half_extents.x, s.half_extents.y, s.half_extents.z}), 1);
      break;
    case ShapeType::kCylinder:
      too_coarse("radius", s.radius, 3);
      too_coarse("width", s.width, 2);
      break;
    case ShapeType::kDisc:
      too_coarse("radius", s.radius, 2);
      too_coarse("thickness", s.width, 1);
      break;
    case ShapeType::kAnnulus:
      too_coarse("radius", s.radius, 2);
      too_coarse("thickness", s.width, 1);
      too_coarse("inner_radius (ring width)", s.radius - s.inner_radius, 1);
      break;
    case ShapeType::kMesh:
      too_coarse("file (mesh extent)", body.bounding_radius(), 2);
      break;
  }
}

// Checks the bodies; returns the largest speed the CFL limit must cover: bodies, free fall over the
// wall height, and the fall of a body that starts above the walls (a drop test) onto the floor.
double check_bodies(const CrmScene& sc, const SceneFail& fail) {
  const CrmBin& bin = sc.bin;
  double speed = std::sqrt(2 * norm(sc.soil.gravity) * bin.size.z);
  for (std::size_t b = 0; b < sc.bodies.size(); ++b) {
    const CrmBody& body = sc.bodies[b];
    const std::string key = fmt::format("bodies[{}] ({})", b, body.name);
    if (!(body.load_ramp >= 0)) fail(key + ".load_ramp", fmt::format("value {} s is negative", body.load_ramp));
    check_body_resolution(body, key, sc.numerics.spacing, fail);
    const Vec3<double>& p = body.position;
    if (p.x < 0 || p.x > bin.size.x || p.y < 0 || p.y > bin.size.y || p.z < 0)
      fail(key + ".position", fmt::format("[{}, {}, {}] is outside the bin [0, {}] x [0, {}] x [0, inf)", p.x, p.y, p.z,
                                          bin.size.x, bin.size.y));
    speed = std::max(speed, body.motion.max_speed(body.bounding_radius()));
    const double lowest = p.z - body.bounding_radius();
    if (lowest > bin.size.z) speed = std::max(speed, std::sqrt(2 * norm(sc.soil.gravity) * lowest));
  }
  return speed;
}

// A given step must respect the CFL limit; none given: the CFL step at the scene's cfl.
void resolve_time_step(CrmScene& sc, double speed, const SceneFail& fail) {
  CrmNumerics& n = sc.numerics;
  n.expected_speed = speed;
  const double limit = n.cfl_limit(sc.soil, speed);
  if (n.time_step < 0)
    fail("resolution.time_step",
         fmt::format("value {} s is negative; expected > 0, or 0 for the CFL step", n.time_step));
  if (n.time_step > 0) {
    if (n.time_step > limit * (1 + 1e-12))
      fail("resolution.time_step", fmt::format("value {} s is above the CFL limit 0.3 h / (c_s + v_max) = {:.4g} s "
                                               "(h = {} m, c_s = {:.4g} m/s, v_max = {:.3g} m/s)",
                                               n.time_step, limit, n.smoothing_length(), sc.soil.sound_speed(), speed));
  } else {
    n.time_step = n.cfl / 0.3 * limit;
  }
}

}  // namespace

void validate_crm_scene(CrmScene& sc) {
  const SceneFail fail{sc.source};
  check_soil(sc.soil, fail);
  check_effects(sc, fail);
  check_settling(sc);
  check_range(CrmRanges::kSpacing, sc.numerics.spacing, "resolution.spacing", sc.source);
  check_range(CrmRanges::kHOverD0, sc.numerics.h_over_d0, "resolution.h_over_d0", sc.source);
  warn_unstable_lattice(sc);
  fit_bin(sc, fail);
  const double speed = check_bodies(sc, fail);
  resolve_time_step(sc, speed, fail);
  if (!(sc.duration >= 0)) fail("duration", "must be >= 0");
}

}  // namespace terracal
