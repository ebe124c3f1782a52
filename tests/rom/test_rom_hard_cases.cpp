// Hard cases stay finite and bounded: standstill (no creep, no jitter), full lock at standstill and
// at speed, reverse, low friction, Moon gravity; a step too large for the fixed-step scheme is an
// error, not NaN.
#include <cmath>

#include <catch2/catch.hpp>

#include "core/errors.hpp"
#include "tests/rom/rom_test_vehicles.hpp"

using namespace terracal;
using namespace terracal::rom;
using namespace terracal::rom::testing;

namespace {
void check_finite(const RomRunResult& r, double max_speed) {
  for (const RomSample& s : r.samples) {
    INFO("t = " << s.time);
    REQUIRE(std::isfinite(s.x));
    REQUIRE(std::isfinite(s.yaw_rate));
    REQUIRE(std::isfinite(s.roll));
    REQUIRE(std::hypot(s.vx, s.vy) < max_speed);
  }
}
}  // namespace

TEST_CASE("rom: 60 s at standstill, straight and at full lock: no creep, no jitter", "[rom][hard]") {
  const RomVehicle v = hmmwv();
  for (RomModel m : {RomModel::k11Dof, RomModel::k18Dof, RomModel::k24Dof})
    for (double steering : {0.0, 1.0}) {
      const RomRunResult r = run(v, constant_inputs(steering, 0, 0), options(m, 60.0, 0.0));
      double max_speed = 0;
      for (const RomSample& s : r.samples) max_speed = std::max(max_speed, std::hypot(s.vx, s.vy));
      INFO(model_name(m) << " steering " << steering << ": max speed " << max_speed);
      CHECK(max_speed < 1e-3);
      CHECK(std::hypot(r.samples.back().x, r.samples.back().y) < 1e-3);
    }
}

TEST_CASE("rom: reverse, low friction, Moon gravity and full lock at speed stay finite", "[rom][hard]") {
  const RomVehicle base = hmmwv();
  SECTION("rolling backwards at 5 m/s comes to rest") {
    const RomRunResult r = run(base, constant_inputs(0.3, 0, 0.2), options(RomModel::k18Dof, 15.0, -5.0));
    check_finite(r, 6.0);
    CHECK(std::fabs(r.samples.back().vx) < 1e-2);
  }
  SECTION("friction 0.1: full throttle and steer") {
    RomVehicle v = base;
    v.friction = 0.1;
    const RomRunResult r = run(v, constant_inputs(0.5, 1, 0), options(RomModel::k18Dof, 10.0, 5.0));
    check_finite(r, 50.0);
    for (const RomSample& s : r.samples) CHECK(std::fabs(s.ay) < 0.2 * v.gravity);
  }
  SECTION("Moon gravity: full throttle and steer") {
    RomVehicle v = base;
    v.gravity = 1.62;
    const RomRunResult r = run(v, constant_inputs(0.5, 1, 0), options(RomModel::k18Dof, 10.0, 3.0));
    check_finite(r, 50.0);
  }
  SECTION("full lock at 25 m/s spins the vehicle without NaN") {
    for (RomModel m : {RomModel::k11Dof, RomModel::k18Dof, RomModel::k24Dof}) {
      const RomRunResult r = run(base, constant_inputs(1, 0, 0), options(m, 10.0, 25.0));
      check_finite(r, 30.0);
      CHECK(std::fabs(r.samples.back().yaw) > 1.0);
    }
  }
}

TEST_CASE("rom: a step too large for the half-implicit scheme is reported, not returned as NaN", "[rom][hard]") {
  RomRunOptions o = options(RomModel::k18Dof, 5.0, 10.0);
  o.step = 0.05;
  o.output_rate = 10;
  CHECK_THROWS_WITH(run(hmmwv(), constant_inputs(0.2, 0.5, 0), o), Catch::Contains("--step"));
}
