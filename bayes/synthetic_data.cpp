#include "bayes/synthetic_data.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "bayes/forward_models.hpp"
#include "core/atomic_file.hpp"
#include "core/errors.hpp"

namespace terracal::bayes {

void validate(const SyntheticDesign& d) {
  using R = SyntheticRanges;
  if (d.plate_radii.empty()) throw InputError("--plates: give at least one plate radius [m]");
  for (double r : d.plate_radii) check_range(R::kPlateRadius, r, "--plates");
  check_distinct(d.plate_radii, "--plates",
                 "each plate radius is run once (plate.csv keys a plate's curve by its radius)");
  check_range(R::kMaxSinkage, d.max_sinkage, "--max-sinkage");
  check_range(R::kAnnulusRadius, d.annulus_inner, "--annulus (inner radius)");
  check_range(R::kAnnulusRadius, d.annulus_outer, "--annulus (outer radius)");
  if (!(d.annulus_outer > d.annulus_inner))
    throw InputError(fmt::format("--annulus {},{}: expected the inner radius below the outer one", d.annulus_inner,
                                 d.annulus_outer));
  if (d.shear_pressures.empty()) throw InputError("--pressures: give at least one normal pressure [Pa]");
  for (double p : d.shear_pressures) check_range(R::kPressure, p, "--pressures");
  check_range(R::kMaxAngle, d.max_angle, "--max-angle");
  check_range(R::kRelativeNoise, d.relative_noise, "--noise");
  for (const auto& [key, n] :
       {std::pair{"--plate-points", d.plate_points}, std::pair{"--shear-points", d.shear_points}})
    if (n < 1 || n > R::kMaxPoints)
      throw InputError(fmt::format("{} {}: expected a whole number in [1, {}]", key, n, R::kMaxPoints));
}

PlateData synthesize_plate(const ParamVector& truth, const SyntheticDesign& d, Rng& rng) {
  PlateData out;
  out.path = "<synthetic plate>";
  out.radii = d.plate_radii;
  for (double r : d.plate_radii) {
    auto add = [&](double z, double f, PlatePhase phase) {
      PlatePoint p;
      p.radius = r;
      p.sinkage = z;
      p.force = f * (1.0 + d.relative_noise * rng.normal());
      p.phase = phase;
      p.fitted = phase == PlatePhase::kLoad;  // reload rows stay below the previous maximum here
      out.points.push_back(p);
    };
    const double area = kPi * r * r;
    // Loading sinkages: the even grid, where a turning point of a cycle replaces a grid point that
    // differs from it by rounding only (0.1 * 6 / 20 is not 0.03), plus the other turning points.
    auto turning = [&](double z) {
      return std::any_of(d.unload_at.begin(), d.unload_at.end(),
                         [&](double u) { return std::abs(u - z) <= 1e-12 * d.max_sinkage; });
    };
    std::vector<double> loading = d.unload_at;
    for (int i = 1; i <= d.plate_points; ++i)
      if (const double z = d.max_sinkage * i / d.plate_points; !turning(z)) loading.push_back(z);
    std::sort(loading.begin(), loading.end());
    for (double z : loading) {
      const double f = plate_force(r, z, truth[kKc], truth[kKphi], truth[kN]);
      add(z, f, PlatePhase::kLoad);
      if (std::find(d.unload_at.begin(), d.unload_at.end(), z) == d.unload_at.end()) continue;
      const double zp = z - f / (area * d.elastic_stiffness);  // plastic sinkage left by unloading
      for (int k = 1; k <= d.unload_points; ++k) {
        const double zk = z - (z - zp) * k / d.unload_points;
        add(zk, k == d.unload_points ? 0.0 : std::max(0.0, area * d.elastic_stiffness * (zk - zp)),
            PlatePhase::kUnload);
      }
      for (int k = 1; k < d.unload_points; ++k) {
        const double zk = zp + (z - zp) * k / d.unload_points;
        add(zk, area * d.elastic_stiffness * (zk - zp), PlatePhase::kReload);
      }
    }
  }
  return out;
}

ShearData synthesize_shear(const ParamVector& truth, const SyntheticDesign& d, Rng& rng) {
  ShearData out;
  out.path = "<synthetic shear>";
  const double area = kPi * (d.annulus_outer * d.annulus_outer - d.annulus_inner * d.annulus_inner);
  for (double pressure : d.shear_pressures)
    for (int i = 1; i <= d.shear_points; ++i) {
      ShearPoint p;
      p.inner_radius = d.annulus_inner;
      p.outer_radius = d.annulus_outer;
      p.normal_load = pressure * area;
      p.angle = d.max_angle * i / d.shear_points;
      p.torque = annulus_torque(p.inner_radius, p.outer_radius, p.normal_load, p.angle, truth[kCohesion],
                                truth[kFriction], truth[kJanosi]) *
                 (1.0 + d.relative_noise * rng.normal());
      out.points.push_back(p);
    }
  return out;
}

void write_plate_csv(const std::string& path, const PlateData& data) {
  // Files without cycles keep the three-column layout (and the demo data set its bytes).
  const bool phases = std::any_of(data.points.begin(), data.points.end(),
                                  [](const PlatePoint& p) { return p.phase != PlatePhase::kLoad; });
  std::string s = phases ? "plate_radius_m,sinkage_m,force_N,phase\n" : "plate_radius_m,sinkage_m,force_N\n";
  for (const auto& p : data.points) {
    s += fmt::format("{},{},{}", p.radius, p.sinkage, p.force);
    if (phases) s += p.phase == PlatePhase::kLoad ? ",load" : p.phase == PlatePhase::kUnload ? ",unload" : ",reload";
    s += "\n";
  }
  write_text_atomically(path, s);
}

void write_shear_csv(const std::string& path, const ShearData& data) {
  std::string s = "inner_radius_m,outer_radius_m,normal_load_N,angle_rad,torque_Nm\n";
  for (const auto& p : data.points)
    s += p.developed
             ? fmt::format("{},{},{},,{}\n", p.inner_radius, p.outer_radius, p.normal_load, p.torque)
             : fmt::format("{},{},{},{},{}\n", p.inner_radius, p.outer_radius, p.normal_load, p.angle, p.torque);
  write_text_atomically(path, s);
}

}  // namespace terracal::bayes
