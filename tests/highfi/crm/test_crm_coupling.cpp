// Validation 11: two-way coupling. A dynamic box resting on the bed is carried by the soil (its
// vertical wrench equals its weight), and in a closed bin the soil's momentum changes by exactly
// the impulse of gravity and of the wall forces (action equals reaction at every marker).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "highfi/crm/crm_solver.hpp"
#include "tests/highfi/crm/crm_test_scenes.hpp"

using namespace terracal;

TEST_CASE("CRM: a dynamic box comes to rest on the bed carrying its weight", "[highfi][crm]") {
  const double d0 = 0.01, mass = 1.5;
  nlohmann::json j = test::bed_scene_json(d0, 14, 8);
  j["bodies"] = {{{"name", "box"},
                  {"shape", {{"type", "box"}, {"size", {0.06, 0.06, 0.03}}}},
                  {"position", {0.07, 0.07, 0.08 + 0.015 + 0.002}},
                  {"motion", {{"type", "dynamic"}}},
                  {"mass", mass},
                  {"inertia", {1e-3, 1e-3, 1e-3}}}};
  CrmSolver s(test::scene_from(j), test::validation_device());
  const double weight = mass * 9.81;
  double sum = 0;
  int count = 0;
  const long n = long(0.4 / s.time_step());
  for (long k = 0; k < n; ++k) {
    s.step();
    if (k >= n - long(0.1 / s.time_step())) {  // mean over the last 0.1 s
      sum += s.wrenches()[0].force.z;
      ++count;
    }
  }
  const double fz = sum / count;
  std::printf("box: mean soil force %.4f N, weight %.4f N, sinkage %.4f m, speed %.2e m/s\n", fz, weight,
              0.097 - s.bodies()[0].position.z, norm(s.bodies()[0].velocity));
  CHECK(s.stats().nonfinite == 0);
  CHECK(fz == Approx(weight).epsilon(0.02));
  CHECK(norm(s.bodies()[0].velocity) < 0.01);
}

TEST_CASE("CRM: soil momentum changes by the impulse of gravity and the walls", "[highfi][crm]") {
  const double d0 = 0.01;
  const CrmScene sc = test::scene_from(test::bed_scene_json(d0, 10, 8));
  // A stress-free start makes the bed fall and slosh: forces are large and far from balance.
  HostSoil bed = initial_bed(sc);
  for (auto& s : bed.s0) s = {0, 0, 0, 0};
  for (std::size_t i = 0; i < bed.size(); ++i) bed.vel[i] = {0.1 * std::sin(37.0 * i), 0.05 * std::cos(11.0 * i), 0, 0};
  CrmSolver s(sc, test::validation_device(), &bed);
  const SoilStats before = s.stats();
  Vec3<double> impulse{}, walls{};
  double scale = 0;
  for (int k = 0; k < 300; ++k) {
    s.step();
    const Vec3<double> g = s.scene().soil.gravity;
    impulse += s.time_step() * (before.mass * g - s.wall_wrench().force);
    walls += s.time_step() * s.wall_wrench().force;
    scale += s.time_step() * before.mass * norm(g);
  }
  const SoilStats after = s.stats();
  const Vec3<double> dp = after.momentum - before.momentum;
  const double err = norm(dp - impulse) / scale;
  std::printf("momentum: dp = (%.6g, %.6g, %.6g), impulse = (%.6g, %.6g, %.6g), relative mismatch %.2e\n", dp.x, dp.y,
              dp.z, impulse.x, impulse.y, impulse.z, err);
  CHECK(after.lost == 0);
  // Exact up to rounding: float64 on the CPU; float32 velocities on the GPU round each update.
  CHECK(err < (test::validation_device() == CrmDevice::kCpu ? 1e-9 : 1e-5));
  // Not trivial: the walls took up most of the weight, and the soil's momentum did change.
  CHECK(norm(walls) > 0.5 * scale);
  CHECK(norm(dp) > 1e-6 * scale);
}
