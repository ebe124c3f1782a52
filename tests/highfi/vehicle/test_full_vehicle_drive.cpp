// The full HMMWV driving on rigid ground: full throttle from rest goes straight with its joints closed,
// and at low speed with a constant steering input it turns on the radius its steering geometry
// predicts (kinematic wheel angles at the ride height, no tire slip).
#include <catch2/catch.hpp>

#include <cmath>

#include "highfi/multibody/mb_integrator.hpp"
#include "highfi/vehicle/steering_kinematics.hpp"
#include "tests/highfi/vehicle/hmmwv_rack.hpp"

using namespace terracal;
using namespace terracal::vehicle;

namespace {
double yaw_of(const mb::RigidBody& b) {
  const mb::Mat3 r = b.rotation();
  return std::atan2(r(1, 0), r(0, 0));
}

// Advances to t in steps of dt, shifting gears between steps.
void drive_to(FullVehicle& v, mb::MbIntegrator& in, double t, double dt, const std::function<void()>& each = {}) {
  for (double at = in.time() + dt; at <= t + 1e-9; at += dt) {
    in.advance(at);
    if (v.update_gear()) in.reinitialize();
    if (each) each();
  }
}
}  // namespace

TEST_CASE("full vehicle: full throttle from rest goes straight", "[vehicle]") {
  const FullVehicleSpec spec = load_full_vehicle("hmmwv");
  FullVehicle v(spec, mb::Vec3(0, 0, spec.tire.unloaded_radius + 0.026));
  v.set_driver([](double t) { return DriverInput{0, t > 0.5 ? 1.0 : 0.0, 0}; });
  mb::MbIntegrator in(v.system(), {5e-8, 5e-10});
  const mb::RigidBody& chassis = v.system().bodies[std::size_t(v.chassis())];
  double violation = 0;
  int shifts = 0, last_gear = 0;
  drive_to(v, in, 4.0, 0.25, [&] {
    violation = std::max(violation, in.constraint_violation());
    shifts += v.driveline().gear != last_gear;
    last_gear = v.driveline().gear;
  });
  INFO("after 3.5 s of full throttle: x "
       << chassis.position.x() << " m, y " << chassis.position.y() << " m, yaw " << yaw_of(chassis) << " rad, speed "
       << chassis.velocity.norm() << " m/s, gear " << v.driveline().gear + 1 << ", constraint error " << violation);
  CHECK(chassis.velocity.x() > 4.0);
  CHECK(shifts >= 1);
  CHECK(std::abs(chassis.position.y()) < 0.01);
  CHECK(std::abs(yaw_of(chassis)) < 1e-3);
  CHECK(violation < 1e-8);
}

namespace {
// A constant steering input of 0.3 at walking speed: the rear axle's path against the radius the
// steering's kinematics predict.
void check_steady_turn(const FullVehicleSpec& spec) {
  FullVehicle v(spec, mb::Vec3(0, 0, spec.tire.unloaded_radius + 0.026));
  mb::MbSystem& s = v.system();
  const int c = v.chassis();
  // A driver aiming at 1 m/s with the throttle (a P gain: it holds 0.7 m/s), braking above 1.2 m/s,
  // steering 0.3 to the left.
  v.set_driver([&s, c](double t) {
    const double speed = s.bodies[std::size_t(c)].velocity.norm();
    return DriverInput{0.3 * std::min(1.0, t / 2), t > 1 ? std::clamp(0.5 * (1.0 - speed), 0.0, 1.0) : 0.0,
                       std::clamp(0.5 * (speed - 1.2), 0.0, 1.0)};
  });
  mb::MbIntegrator in(s, {1e-5, 1e-7});
  drive_to(v, in, 8.0, 0.5);
  // The rear axle's centre, sampled over the next 12 s, and a circle through its path.
  // (The chassis body's frame is the chassis frame, with its origin at the centre of mass.)
  const mb::Vec3 rear_local = mb::Vec3(spec.axles.back().location.x(), 0, 0) - spec.chassis.com;
  std::vector<mb::Vec3> path;
  drive_to(v, in, 20.0, 0.5, [&] { path.push_back(s.bodies[std::size_t(c)].point(rear_local)); });
  Eigen::MatrixXd a(path.size(), 3);
  Eigen::VectorXd b(path.size());
  for (std::size_t k = 0; k < path.size(); ++k) {
    a.row(Eigen::Index(k)) << 2 * path[k].x(), 2 * path[k].y(), 1;
    b[Eigen::Index(k)] = path[k].head<2>().squaredNorm();
  }
  const Eigen::Vector3d fit = a.colPivHouseholderQr().solve(b);
  const double radius = std::sqrt(fit[2] + fit[0] * fit[0] + fit[1] * fit[1]);
  // The prediction: the wheels' kinematic angles at the arm's angle and the ride height.
  const mb::RigidBody& chassis = s.bodies[std::size_t(c)];
  double travel = 0;
  for (const WishboneSide& w : v.corners()) {
    const mb::Vec3 local =
        chassis.rotation().transpose() * (s.bodies[std::size_t(w.spindle)].position - chassis.position);
    travel += local.z() + spec.chassis.com.z() - (-0.026);  // the spindles' design height is -0.026 m
  }
  travel /= double(v.corners().size());
  const SteerAngles k = steering_kinematics(spec, {steering_position(v)}, travel)[0];
  const double wheelbase = spec.axles.front().location.x() - spec.axles.back().location.x();
  const double predicted = predicted_turn_radius(k.left, k.right, 2 * 0.91, wheelbase);
  INFO("path radius " << radius << " m; predicted " << predicted << " m (wheels " << k.left << ", " << k.right
                      << " rad at travel " << travel << " m); speed " << chassis.velocity.norm() << " m/s");
  CHECK(std::abs(radius - predicted) / predicted < 0.03);
  CHECK(radius > 10);
  CHECK(radius < 20);
}
}  // namespace

TEST_CASE("full vehicle: a constant steering input at walking speed turns on the radius the steering predicts",
          "[vehicle]") {
  check_steady_turn(load_full_vehicle("hmmwv"));
}

TEST_CASE("full vehicle: with rack-and-pinion steering it turns on the radius the steering predicts", "[vehicle]") {
  check_steady_turn(test::hmmwv_with_rack());
}
