#pragma once
// Validation 9's measurement: the force on a circular plate (radius 0.1 m) pushed at constant
// speed into a settled bed, read at 2 cm sinkage. The force is taken from a straight-line fit of
// force against sinkage over 1.5-2.5 cm, which averages out the step-to-step noise of SPH forces
// without biasing a force that grows smoothly with sinkage.
#include <cstdio>
#include <vector>

#include "highfi/crm/crm_run.hpp"
#include "highfi/crm/crm_solver.hpp"
#include "tests/highfi/crm/crm_test_scenes.hpp"

namespace terracal::test {

struct PlateBin {
  double side = 0.4, depth = 0.15;   // bin side (x = y) and soil depth [m]
  double radius = 0.1, speed = 0.1;  // plate radius [m] and push speed [m/s]
};

// The scene at spacing d0; the plate's bottom face starts on the soil surface.
inline nlohmann::json plate_bin_scene(double d0, const PlateBin& b) {
  const int cells = int(b.side / d0 + 0.5), layers = int(b.depth / d0 + 0.5);
  nlohmann::json j = bed_scene_json(d0, cells, layers, 0.05);
  j["resolution"]["cpu_precision"] = "float";
  const double surface = layers * d0, thickness = 0.02;
  const double centre = 0.5 * cells * d0;
  j["bodies"] = {{{"name", "plate"},
                  {"shape", {{"type", "disc"}, {"radius", b.radius}, {"thickness", thickness}}},
                  {"position", {centre, centre, surface + 0.5 * thickness}},
                  {"motion", {{"type", "prescribed"}, {"linear_velocity", {0, 0, -b.speed}}}}}};
  return j;
}

struct PlateForce {
  double d0 = 0, force = 0;  // spacing and force at 2 cm sinkage [N]
  std::size_t particles = 0;
  long steps = 0;
};

inline PlateForce plate_force_at_2cm(double d0, const PlateBin& b, CrmDevice device) {
  const CrmScene sc = scene_from(plate_bin_scene(d0, b));
  const HostSoil bed = settled_bed(sc, device, {});
  CrmSolver s(sc, device, &bed);
  const double z0 = s.bodies()[0].position.z;
  // Least-squares line F = a + c (sinkage - 2 cm) over sinkages 1.5-2.5 cm.
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (;;) {
    s.step();
    const double sink = z0 - s.bodies()[0].position.z;
    if (sink > 0.025) break;
    if (sink < 0.015) continue;
    const double x = sink - 0.02, y = s.wrenches()[0].force.z;
    n += 1;
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  PlateForce r;
  r.d0 = d0;
  r.force = (sy - slope * sx) / n;
  r.particles = s.engine().soil_count();
  r.steps = s.steps();
  std::printf("plate r=%.2f m, d0=%.4f m: %zu particles, %ld steps, force at 2 cm sinkage %.2f N (slope %.0f N/m)%s\n",
              b.radius, d0, r.particles, r.steps, r.force, slope, s.stats().nonfinite ? "  NON-FINITE" : "");
  return r;
}

}  // namespace terracal::test
