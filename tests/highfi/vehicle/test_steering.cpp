// The Pitman-arm steering of the HMMWV: the steered wheels' angles and the Ackermann error from a
// kinematic solve agree with the dynamic vehicle whose steering servo holds the arm, chassis held and
// wheel centres held at their design heights by posts.
#include <catch2/catch.hpp>

#include <cmath>

#include "highfi/multibody/mb_integrator.hpp"
#include "highfi/vehicle/steering_kinematics.hpp"
#include "tests/highfi/vehicle/wheel_posts.hpp"

using namespace terracal;
using namespace terracal::vehicle;

TEST_CASE("steering: the HMMWV's wheel angles and Ackermann error, kinematic against dynamic", "[vehicle]") {
  const FullVehicleSpec spec = load_full_vehicle("hmmwv");
  const double max_arm = spec.steering.max_angle;
  const auto kin = steering_kinematics(spec, {-max_arm, -0.5 * max_arm, 0.0, 0.5 * max_arm, max_arm});
  for (const auto& k : kin)
    UNSCOPED_INFO("arm " << k.position * 180 / M_PI << " deg: left " << k.left * 180 / M_PI << ", right "
                         << k.right * 180 / M_PI << " deg, Ackermann error " << k.ackermann_error * 180 / M_PI
                         << " deg");
  // Straight ahead at the arm's zero; both wheels turn the same way, by tens of degrees at full lock.
  CHECK(std::abs(kin[2].left) < 1e-6);
  CHECK(std::abs(kin[2].right) < 1e-6);
  CHECK(kin[4].left * kin[4].right > 0);
  CHECK(std::abs(kin[4].left) > 0.35);
  CHECK(kin[0].left * kin[4].left < 0);
  // The arm turned clockwise (negative) turns left: the left wheel, inside, turns more.
  CHECK(kin[0].left > 0);
  CHECK(kin[0].left > kin[0].right);
  CHECK(kin[4].right < kin[4].left);

  // The dynamic vehicle, chassis held, posts under the wheels, steering servo at half input.
  FullVehicle v(spec, mb::Vec3(0, 0, 10.0));
  test::hold_on_posts(v);
  mb::MbSystem& s = v.system();
  v.set_driver([](double t) { return DriverInput{std::min(1.0, t) * 0.5, 0, 0}; });
  mb::MbIntegrator in(s, {1e-8, 1e-10});
  in.advance(3.0);
  const double arm = pitman_arm_angle(s, v.steering());
  const auto at = steering_kinematics(spec, {arm})[0];
  const double left = steer_angle(s.bodies[std::size_t(v.corners()[0].spindle)]);
  const double right = steer_angle(s.bodies[std::size_t(v.corners()[1].spindle)]);
  INFO("arm " << arm << " rad (servo target " << 0.5 * max_arm << "); dynamic left " << left << ", right " << right
              << "; kinematic " << at.left << ", " << at.right);
  CHECK(std::abs(arm + 0.5 * max_arm) < 1e-3);  // the servo holds the arm (clockwise to steer left)
  CHECK(left > right);                          // a left turn: the left wheel inside
  // The posts hold the wheel centres within ~1e-4 m of their design heights: the angles agree to that.
  CHECK(std::abs(left - at.left) < 1e-3);
  CHECK(std::abs(right - at.right) < 1e-3);
}
