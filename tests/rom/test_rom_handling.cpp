// Handling of the reduced-order models against closed-form answers: low-speed kinematic turning
// and the linear bicycle model's steady yaw-rate gain and understeer gradient.
#include <cmath>

#include <catch2/catch.hpp>

#include "rom/rom11.hpp"
#include "rom/rom18.hpp"
#include "tests/rom/rom_test_vehicles.hpp"

using namespace terracal;
using namespace terracal::rom;
using namespace terracal::rom::testing;

namespace {
// Axle cornering stiffness of the linear bicycle model: two tires' initial lateral slope at their
// static load (TMeasy's dfy0 at that load, per radian of slip angle).
double axle_cornering_stiffness(const RomVehicle& v, int axle) {
  const double fz_axle = axle == 0 ? axle_loads(v, 0).front : axle_loads(v, 0).rear;
  const TmeasyLoadState st = tmeasy_at_load(v.tire[axle], 0.5 * fz_axle);
  return 2.0 * st.y.df0;
}
}  // namespace

TEST_CASE("rom: at 2 m/s under a small constant steer the path radius is wheelbase / tan(delta)", "[rom]") {
  const RomVehicle v = frictionless_hmmwv();
  for (RomModel m : {RomModel::k11Dof, RomModel::k18Dof, RomModel::k24Dof}) {
    const double steering = 0.05, delta = steering * v.max_steer;
    const RomRunResult r = run(v, constant_inputs(steering, 0, 0), options(m, 20.0, 2.0));
    const RomSample& s = r.samples.back();
    const double radius = std::hypot(s.vx, s.vy) / s.yaw_rate;
    INFO(model_name(m) << ": radius " << radius << " m, kinematic " << v.wheelbase() / std::tan(delta) << " m");
    CHECK(radius == Approx(v.wheelbase() / std::tan(delta)).epsilon(0.03));
  }
}

TEST_CASE("rom: steady yaw-rate gain matches the linear bicycle model below 0.3 g, the understeer has its sign",
          "[rom]") {
  RomVehicle v = frictionless_hmmwv();
  // Front-heavy: the front axle's cornering stiffness grows less than its load (TMeasy's degressive
  // load dependence), so the vehicle understeers (K > 0).
  v.cg_to_front = 1.3;
  v.cg_to_rear = 2.0;
  const double l = v.wheelbase(), g = v.gravity;
  const double cf = axle_cornering_stiffness(v, 0), cr = axle_cornering_stiffness(v, 1);
  const double k_us = axle_loads(v, 0).front / g / cf - axle_loads(v, 0).rear / g / cr;
  REQUIRE(k_us > 0);
  for (RomModel m : {RomModel::k11Dof, RomModel::k18Dof, RomModel::k24Dof}) {
    for (double speed : {10.0, 20.0}) {
      const double steering = 0.02, delta = steering * v.max_steer;
      const RomRunResult r = run(v, constant_inputs(steering, 0, 0), options(m, 6.0, speed));
      const RomSample& s = r.samples.back();
      REQUIRE(std::fabs(s.ay) < 0.3 * g);
      const double gain = s.yaw_rate / delta, bicycle = s.vx / (l + k_us * s.vx * s.vx);
      INFO(model_name(m) << " at " << s.vx << " m/s: gain " << gain << " 1/s, bicycle " << bicycle << ", neutral "
                         << s.vx / l << ", ay " << s.ay);
      CHECK(gain == Approx(bicycle).epsilon(0.05));
      CHECK(gain < s.vx / l);  // understeer: less yaw rate than a neutral vehicle
    }
  }
}
