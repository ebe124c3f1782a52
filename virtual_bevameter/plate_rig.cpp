#include "virtual_bevameter/plate_rig.hpp"

#include <cmath>

#include <fmt/format.h>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "virtual_bevameter/rig_checks.hpp"

namespace terracal::rigs {

void validate(const PlateTest& t) {
  check_range("plate radius", t.radius, 1e-3, 10, "m");
  check_range("plate max_sinkage", t.max_sinkage, 1e-4, t.radius * 5, "m (at most 5 plate radii)");
  check_range("plate speed", t.speed, 1e-4, 10, "m/s");
  if (t.unload_speed != 0) check_range("plate unload_speed", t.unload_speed, 1e-4, 10, "m/s (0: as the plate speed)");
  check_range("plate unload_at", t.unload_at, 0, 0.95, "(fraction of max_sinkage; 0 = no unload cycle)");
  check_range("plate unload_depth", t.unload_depth, 0, 1, "(fraction of the sinkage reached)");
  check_range("plate thickness", t.thickness, 1e-4, 1, "m");
  check_range("plate samples", t.samples, 2, 1e6, "");
}

std::vector<PlateRow> run_plate(const TerrainSite& site, const PlateTest& test, const RigProgress& progress) {
  validate(test);
  // The stroke: down to the unload point, up by the unload depth, down again to the maximum (the
  // lift and its way back at the unload speed).
  struct Leg {
    double duration, velocity;
  };
  std::vector<Leg> legs;
  if (test.unload_at > 0 && test.unload_depth > 0) {
    const double z_u = test.unload_at * test.max_sinkage, lift = test.unload_depth * z_u;
    const double v_u = test.unload_speed > 0 ? test.unload_speed : test.speed;
    if (v_u == test.speed)
      legs = {{z_u / test.speed, -test.speed},
              {lift / test.speed, test.speed},
              {(test.max_sinkage - z_u + lift) / test.speed, -test.speed}};
    else
      legs = {{z_u / test.speed, -test.speed},
              {lift / v_u, v_u},
              {lift / v_u, -v_u},
              {(test.max_sinkage - z_u) / test.speed, -test.speed}};
  } else {
    legs = {{test.max_sinkage / test.speed, -test.speed}};
  }
  RigidBody plate;
  plate.name = fmt::format("plate r={}", test.radius);
  plate.shape.type = ShapeType::kDisc;
  plate.shape.radius = test.radius;
  plate.shape.width = test.thickness;
  const Vec3<double> c = site.centre();
  plate.position = {c.x, c.y, site.surface_height() + 0.5 * test.thickness};
  plate.mass = 1;
  plate.inertia = {1, 1, 1};
  double duration = 0;
  for (const Leg& l : legs) {
    plate.motion.schedule.push_back({l.duration, {0, 0, l.velocity}, {}});
    duration += l.duration;
  }
  plate.motion.linear_velocity = {0, 0, legs[0].velocity};
  check_fits(site, plate, test.radius, test.radius);

  auto terrain = site.make({plate}, duration);
  const double dt = terrain->time_step();
  const long steps = long(std::ceil(duration / dt - 1e-9));
  const long every = std::max(1L, steps / test.samples);
  std::vector<PlateRow> rows;
  // The phase follows the plate's actual displacement over the last step (the terrain decides at
  // which step a leg of the schedule begins, and may report the new leg's velocity for a step that
  // still moved the plate with the old one): down before any lift is load, up is unload, down after
  // a lift is reload.
  // Each leg's turning point is recorded too (the row before the phase changes), so the deepest
  // sinkage of the load leg is in the file and no unload row lies below it.
  bool lifted = false;
  const char* last_phase = "load";
  PlateRow previous;
  bool previous_recorded = true;
  for (long s = 1; s <= steps; ++s) {
    const double z_before = terrain->bodies()[0].position.z;
    terrain->step();
    const BodyState& b = terrain->bodies()[0];
    const double dz = b.position.z - z_before;
    if (dz > 0) lifted = true;
    const char* phase = dz > 0 ? "unload" : dz < 0 ? (lifted ? "reload" : "load") : last_phase;
    const PlateRow row{test.radius, site.surface_height() - (b.position.z - 0.5 * test.thickness),
                       terrain->wrenches()[0].force.z, phase};
    if (std::string(phase) != last_phase && !previous_recorded) rows.push_back(previous);
    last_phase = phase;
    previous = row;
    previous_recorded = s % every == 0 || s == steps;
    if (!previous_recorded) continue;
    rows.push_back(row);
    if (progress) progress(plate.name, terrain->time(), duration);
  }
  return rows;
}

void write_plate_csv(const std::string& path, const std::vector<PlateRow>& rows) {
  std::string s = "plate_radius_m,sinkage_m,force_N,phase\n";
  for (const auto& r : rows) s += fmt::format("{:.9g},{:.9g},{:.9g},{}\n", r.radius, r.sinkage, r.force, r.phase);
  write_text_atomically(path, s);
}

}  // namespace terracal::rigs
