// Prescribed motion as a function of time. A plate follows a velocity schedule: pushed
// into the bed, pulled back a little, then held. Its position follows the integral of the schedule,
// the soil's force builds up while loading and falls steeply on unloading (the elastic rebound
// that gives SCM its unloading stiffness), and a held plate stays put.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "highfi/crm/crm_solver.hpp"
#include "tests/highfi/crm/crm_test_scenes.hpp"

using namespace terracal;

TEST_CASE("CRM: a prescribed body follows a velocity schedule", "[highfi][crm]") {
  nlohmann::json j = test::bed_scene_json(0.01, 14, 8, 0.0);
  j["resolution"]["cpu_precision"] = "float";
  const double z0 = 0.08 + 0.01;
  j["bodies"] = {{{"name", "plate"},
                  {"shape", {{"type", "disc"}, {"radius", 0.04}, {"thickness", 0.02}}},
                  {"position", {0.07, 0.07, z0}},
                  {"motion",
                   {{"type", "prescribed"},
                    {"schedule",
                     {{{"duration", 0.1}, {"linear_velocity", {0, 0, -0.2}}},
                      {{"duration", 0.03}, {"linear_velocity", {0, 0, 0.1}}}}}}}}};
  CrmSolver s(test::scene_from(j), test::validation_device());
  double peak = 0;
  while (s.time() < 0.1 - 1e-9) {
    s.step();
    peak = std::max(peak, s.wrenches()[0].force.z);
  }
  const double z_loaded = s.bodies()[0].position.z, f_loaded = s.wrenches()[0].force.z;
  while (s.time() < 0.13 - 1e-9) s.step();
  const double z_unloaded = s.bodies()[0].position.z, f_unloaded = s.wrenches()[0].force.z;
  for (int k = 0; k < 50; ++k) s.step();
  const double z_held = s.bodies()[0].position.z;
  std::printf(
      "schedule: plate at %.5f m (loaded, expected %.5f), %.5f m (unloaded, expected %.5f), held at %.5f m; "
      "force %.2f N loaded (peak %.2f N), %.2f N after pulling back 3 mm\n",
      z_loaded, z0 - 0.02, z_unloaded, z0 - 0.017, z_held, f_loaded, peak, f_unloaded);
  // Within one step's travel of the exact integral (the switch falls inside a step).
  const double one_step = 0.3 * s.time_step();
  CHECK(std::abs(z_loaded - (z0 - 0.02)) < one_step);
  CHECK(std::abs(z_unloaded - (z0 - 0.017)) < one_step);
  CHECK(z_held == z_unloaded);
  CHECK(norm(s.bodies()[0].velocity) == 0.0);
  CHECK(f_loaded > 10.0);
  CHECK(f_unloaded < 0.3 * f_loaded);
  CHECK(s.stats().nonfinite == 0);
}
