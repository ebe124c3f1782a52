// The rack-and-pinion steering template: its kinematics (straight at zero travel, a left input turns
// both wheels left, mirrored to the right), the servo holding the rack where the input puts it with the
// wheels at the kinematic angles, and the template's bad inputs.
#include <catch2/catch.hpp>

#include <cmath>

#include "highfi/multibody/mb_integrator.hpp"
#include "highfi/vehicle/steering_kinematics.hpp"
#include "tests/highfi/vehicle/hmmwv_rack.hpp"
#include "tests/highfi/vehicle/wheel_posts.hpp"

using namespace terracal;
using namespace terracal::vehicle;

TEST_CASE("rack-and-pinion: the wheels' angles against the rack's travel", "[vehicle]") {
  const FullVehicleSpec spec = test::hmmwv_with_rack();
  REQUIRE(spec.rack_steering);
  CHECK(spec.rack.max_travel() == Approx(0.087));
  const auto kin = steering_kinematics(spec, {steering_position(spec, 1.0), 0.0, steering_position(spec, -1.0)});
  for (const auto& k : kin)
    UNSCOPED_INFO("travel " << k.position << " m: left " << k.left * 180 / M_PI << ", right " << k.right * 180 / M_PI
                            << " deg, Ackermann error " << k.ackermann_error * 180 / M_PI << " deg");
  CHECK(std::abs(kin[1].left) < 1e-6);
  CHECK(std::abs(kin[1].right) < 1e-6);
  // Full left: both wheels left by tens of degrees; full right mirrors it. (With the HMMWV's tie rods on
  // a rack that only slides, the outer wheel turns ~2.6 degrees more than the inner: the Pitman arm's
  // link also swings, which gives that layout its Ackermann sense.)
  CHECK(kin[0].left > 0.3);
  CHECK(kin[0].right > 0.3);
  CHECK(kin[2].left < -0.3);
  CHECK(kin[2].right < -0.3);
  CHECK(std::abs(kin[0].left + kin[2].right) < 1e-6);  // mirrored: the layout is symmetric
  CHECK(std::abs(kin[0].right + kin[2].left) < 1e-6);
}

TEST_CASE("rack-and-pinion: the pinion's servo holds the rack at the input's travel", "[vehicle]") {
  const FullVehicleSpec spec = test::hmmwv_with_rack();
  FullVehicle v(spec, mb::Vec3(0, 0, 10.0));  // in the air, chassis held, posts under the wheel centres
  test::hold_on_posts(v);
  mb::MbSystem& s = v.system();
  v.set_driver([](double t) { return DriverInput{0.5 * std::min(1.0, t), 0, 0}; });
  mb::MbIntegrator in(s, {1e-8, 1e-10});
  in.advance(3.0);
  const double travel = steering_position(v);
  const double left = steer_angle(s.bodies[std::size_t(v.corners()[0].spindle)]);
  const double right = steer_angle(s.bodies[std::size_t(v.corners()[1].spindle)]);
  const SteerAngles k = steering_kinematics(spec, {travel})[0];
  INFO("travel " << travel << " m against " << steering_position(spec, 0.5) << " m; dynamic " << left << ", " << right
                 << " rad; kinematic " << k.left << ", " << k.right << " rad");
  // The servo (1e7 N/m) gives a little to the tie rods' push (a few kN): within 1 % of the full travel.
  CHECK(std::abs(travel - steering_position(spec, 0.5)) < 1e-3);
  CHECK(in.constraint_violation() < 1e-8);
  CHECK(left > 0.1);  // a left turn
  // The posts hold the wheel centres within ~1e-4 m of their design heights: the angles agree to that.
  CHECK(std::abs(left - k.left) < 1e-3);
  CHECK(std::abs(right - k.right) < 1e-3);
}

TEST_CASE("rack-and-pinion: bad template values are refused with the key named", "[vehicle]") {
  nlohmann::json j = test::hmmwv_rack_json();
  j["steering"]["pinion"]["radius"] = -0.1;
  CHECK_THROWS_WITH(read_full_vehicle(j, "v.json"),
                    Catch::Contains("steering.pinion.radius") && Catch::Contains("-0.1"));
  j = test::hmmwv_rack_json();
  j["steering"]["axis"] = {0, 0, 0};
  CHECK_THROWS_WITH(read_full_vehicle(j, "v.json"), Catch::Contains("steering.axis") && Catch::Contains("zero"));
  j = test::hmmwv_rack_json();
  j["steering"]["template"] = "worm_gear";
  CHECK_THROWS_WITH(read_full_vehicle(j, "v.json"),
                    Catch::Contains("steering.template") && Catch::Contains("worm_gear"));
  j = test::hmmwv_rack_json();
  j["steering"]["idler"] = 1;  // a Pitman arm's key
  CHECK_THROWS_WITH(read_full_vehicle(j, "v.json"), Catch::Contains("steering.idler"));
}
