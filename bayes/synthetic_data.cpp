#include "bayes/synthetic_data.hpp"

#include <fmt/format.h>

#include "bayes/forward_models.hpp"
#include "core/atomic_file.hpp"

namespace terracal::bayes {

PlateData synthesize_plate(const ParamVector& truth, const SyntheticDesign& d, Rng& rng) {
  PlateData out;
  out.path = "<synthetic plate>";
  out.radii = d.plate_radii;
  for (double r : d.plate_radii)
    for (int i = 1; i <= d.plate_points; ++i) {
      PlatePoint p;
      p.radius = r;
      p.sinkage = d.max_sinkage * i / d.plate_points;
      p.force = plate_force(r, p.sinkage, truth[kKc], truth[kKphi], truth[kN]) * (1.0 + d.relative_noise * rng.normal());
      p.fitted = true;
      out.points.push_back(p);
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
      p.torque = annulus_torque(p.inner_radius, p.outer_radius, p.normal_load, p.angle, truth[kCohesion], truth[kFriction],
                                truth[kJanosi]) *
                 (1.0 + d.relative_noise * rng.normal());
      out.points.push_back(p);
    }
  return out;
}

void write_plate_csv(const std::string& path, const PlateData& data) {
  std::string s = "plate_radius_m,sinkage_m,force_N\n";
  for (const auto& p : data.points) s += fmt::format("{},{},{}\n", p.radius, p.sinkage, p.force);
  write_text_atomically(path, s);
}

void write_shear_csv(const std::string& path, const ShearData& data) {
  std::string s = "inner_radius_m,outer_radius_m,normal_load_N,angle_rad,torque_Nm\n";
  for (const auto& p : data.points)
    s += p.developed ? fmt::format("{},{},{},,{}\n", p.inner_radius, p.outer_radius, p.normal_load, p.torque)
                     : fmt::format("{},{},{},{},{}\n", p.inner_radius, p.outer_radius, p.normal_load, p.angle, p.torque);
  write_text_atomically(path, s);
}

}  // namespace terracal::bayes
