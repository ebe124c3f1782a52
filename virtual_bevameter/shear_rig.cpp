#include "virtual_bevameter/shear_rig.hpp"

#include <cmath>

#include <fmt/format.h>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "virtual_bevameter/rig_checks.hpp"

namespace terracal::rigs {

void validate(const ShearTest& t) {
  check_range("annulus inner_radius", t.inner_radius, 0, 10, "m");
  check_range("annulus outer_radius", t.outer_radius, t.inner_radius + 1e-3, 10, "m (above the inner radius)");
  if (t.loads.empty()) throw InputError("shear loads: empty; give at least one normal load");
  for (double l : t.loads) check_range("shear load", l, 1e-3, 1e7, "N");
  check_range("shear angular_velocity", t.angular_velocity, 1e-3, 100, "rad/s");
  check_range("shear max_angle", t.max_angle, 1e-3, 100, "rad");
  check_range("shear settle_time", t.settle_time, 0, 100, "s");
  check_range("shear load_ramp", t.load_ramp, 0, t.settle_time, "s (within the settling under the load)");
  check_range("shear thickness", t.thickness, 1e-4, 1, "m");
  check_range("shear samples", t.samples, 2, 1e6, "");
}

std::vector<ShearRow> run_shear(const TerrainSite& site, const ShearTest& test, const RigProgress& progress) {
  validate(test);
  const double g = norm(site.gravity());
  if (!(g > 0)) throw InputError("annulus shear under a dead load needs gravity: the site has |g| = 0");
  const double turn = test.max_angle / test.angular_velocity, duration = test.settle_time + turn;
  std::vector<ShearRow> rows;
  for (const double load : test.loads) {
    RigidBody a;
    a.name = fmt::format("annulus {}-{} m under {} N", test.inner_radius, test.outer_radius, load);
    a.shape.type = ShapeType::kAnnulus;
    a.shape.radius = test.outer_radius;
    a.shape.inner_radius = test.inner_radius;
    a.shape.width = test.thickness;
    const Vec3<double> c = site.centre();
    a.position = {c.x, c.y, site.surface_height() + 0.5 * test.thickness};
    // The dead load is the annulus's weight; only the vertical axis is free.
    a.mass = load / g;
    const double r2 = test.outer_radius * test.outer_radius + test.inner_radius * test.inner_radius;
    a.inertia = {a.mass * r2 / 4, a.mass * r2 / 4, a.mass * r2 / 2};
    a.load_ramp = test.load_ramp;
    a.motion.free = {false, false, true, false, false, false};
    a.motion.schedule = {{test.settle_time, {}, {}}, {turn, {}, {0, 0, test.angular_velocity}}};
    check_fits(site, a, test.outer_radius, test.outer_radius);

    auto terrain = site.make({a}, duration);
    const double dt = terrain->time_step();
    const long steps = long(std::ceil(duration / dt - 1e-9));
    const long settle_steps = long(std::floor(test.settle_time / dt + 1e-9));
    const long every = std::max(1L, (steps - settle_steps) / test.samples);
    for (long s = 1; s <= steps; ++s) {
      terrain->step();
      if (s <= settle_steps || (s - settle_steps) % every != 0) continue;  // rows once the annulus turns
      const BodyState& b = terrain->bodies()[0];
      const double angle = test.angular_velocity * std::max(0.0, terrain->time() - test.settle_time);
      rows.push_back({test.inner_radius, test.outer_radius, load, angle, -terrain->wrenches()[0].torque.z,
                      site.surface_height() - (b.position.z - 0.5 * test.thickness)});
      if (progress) progress(a.name, terrain->time(), duration);
    }
  }
  return rows;
}

void write_shear_csv(const std::string& path, const std::vector<ShearRow>& rows) {
  std::string s = "inner_radius_m,outer_radius_m,normal_load_N,angle_rad,torque_Nm,sinkage_m\n";
  for (const auto& r : rows)
    s += fmt::format("{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n", r.inner_radius, r.outer_radius, r.normal_load,
                     r.angle, r.torque, r.sinkage);
  write_text_atomically(path, s);
}

}  // namespace terracal::rigs
