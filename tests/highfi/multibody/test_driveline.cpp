// Multibody core, the driveline's shafts: a gear, an open differential, a clutch that slips then locks,
// and a shaft driving a wheel body, each against its closed-form motion.
#include <catch2/catch.hpp>

#include <cmath>

#include "highfi/multibody/mb_integrator.hpp"
#include "tests/highfi/multibody/mb_test_systems.hpp"

using namespace terracal;
using namespace terracal::mb;

namespace {
int add_shaft(MbSystem& s, const std::string& name, double inertia, double speed = 0) {
  s.shafts.push_back({name, inertia, 0.0, speed});
  return int(s.shafts.size()) - 1;
}
void constant_torque(MbSystem& s, int shaft, double torque) {
  s.shaft_torques.push_back({"torque", shaft, [torque](double, double, double) { return torque; }});
}
}  // namespace

TEST_CASE("multibody: a gear shares a torque's work as the reflected inertia says", "[multibody][driveline]") {
  const double i1 = 0.2, i2 = 1.5, r = 0.25, torque = 40;  // w_out = r w_in
  MbSystem s;
  const int in = add_shaft(s, "in", i1), out = add_shaft(s, "out", i2);
  s.linkages.push_back(gear("gear", in, out, r));
  constant_torque(s, in, torque);
  MbIntegrator integ(s, {1e-10, 1e-12});
  integ.advance(2.0);
  const double alpha = torque / (i1 + r * r * i2);
  INFO("input " << s.shafts[0].speed << " rad/s, expected " << alpha * 2 << "; output " << s.shafts[1].speed);
  CHECK(std::abs(s.shafts[0].speed - alpha * 2) < 1e-8 * alpha * 2);
  CHECK(std::abs(s.shafts[1].speed - r * s.shafts[0].speed) < 1e-10 * alpha * 2);
  CHECK(std::abs(s.mechanical_energy() - torque * s.shafts[0].angle) < 1e-7 * torque * s.shafts[0].angle);
}

TEST_CASE("multibody: an open differential sends equal torques to unequal wheels", "[multibody][driveline]") {
  const double ic = 0.3, il = 1.0, ir = 3.0, torque = 100;
  MbSystem s;
  const int c = add_shaft(s, "case", ic), l = add_shaft(s, "left", il), r = add_shaft(s, "right", ir);
  s.linkages.push_back(differential("diff", c, l, r));
  constant_torque(s, c, torque);
  MbIntegrator integ(s, {1e-10, 1e-12});
  integ.advance(1.5);
  // I_c a_c = T - 2 tau, I_l a_l = tau = I_r a_r, a_l + a_r = 2 a_c: each side takes
  // tau = T / (2 + I_c (1/I_l + 1/I_r) / 2).
  const double tau = torque / (2 + ic * (1 / il + 1 / ir) / 2);
  INFO("left " << s.shafts[1].speed << ", right " << s.shafts[2].speed << ", case " << s.shafts[0].speed);
  CHECK(std::abs(s.shafts[1].speed - tau / il * 1.5) < 1e-8 * tau / il * 1.5);
  CHECK(std::abs(s.shafts[2].speed - tau / ir * 1.5) < 1e-8 * tau / il * 1.5);
  CHECK(std::abs(s.shafts[1].speed + s.shafts[2].speed - 2 * s.shafts[0].speed) < 1e-9);
}

TEST_CASE("multibody: a clutch slips at its torque limit, then locks", "[multibody][driveline]") {
  const double ib = 0.5, tmax = 20, w = 100;  // the engine side: a flywheel of 1e6 kg m^2 at 100 rad/s
  MbSystem s;
  const int a = add_shaft(s, "engine", 1e6, w), b = add_shaft(s, "gearbox", ib);
  s.clutches.push_back({"clutch", a, b, tmax, 1e3});
  MbIntegrator integ(s, {1e-9, 1e-10});
  const double t_lock = w * ib / tmax;  // 2.5 s
  integ.advance(0.5 * t_lock);
  INFO("slipping: " << s.shafts[1].speed << " rad/s, expected " << tmax / ib * 0.5 * t_lock);
  CHECK(std::abs(s.shafts[1].speed - tmax / ib * 0.5 * t_lock) < 1e-6 * w);
  integ.advance(1.5 * t_lock);
  INFO("locked: " << s.shafts[1].speed << " against " << s.shafts[0].speed);
  CHECK(std::abs(s.shafts[1].speed - s.shafts[0].speed) < 1e-6 * w);
  CHECK(std::abs(s.shafts[0].speed - w) < 1e-4);  // the flywheel gave up 0.5 I_b w^2 / 1e6 of speed
}

TEST_CASE("multibody: a shaft spins a wheel body on its axle", "[multibody][driveline]") {
  MbSystem s;
  s.gravity = Vec3::Zero();
  const int g = test::add_ground(s);
  RigidBody wheel;
  wheel.mass = 20;
  wheel.inertia = Vec3(0.8, 1.6, 0.8).asDiagonal();  // spins about its body y
  wheel.position = Vec3(1, 0, 0.4);
  const int wb = s.add_body(wheel);
  s.add_joint("axle", JointType::revolute, g, wb, wheel.position, test::axes_z(Vec3::UnitY()));
  const int axle = add_shaft(s, "axle shaft", 0.4);
  s.shaft_bodies.push_back({"wheel", axle, g, wb, Vec3::UnitY()});
  constant_torque(s, axle, 50);
  MbIntegrator integ(s, {1e-10, 1e-12});
  integ.advance(3.0);
  const double expected = 50.0 / (0.4 + 1.6) * 3.0;
  INFO("wheel " << s.bodies[1].omega.transpose() << " rad/s; shaft " << s.shafts[0].speed << "; expected " << expected);
  CHECK(std::abs(s.shafts[0].speed - expected) < 1e-8 * expected);
  CHECK(std::abs(s.bodies[1].omega.y() - expected) < 1e-8 * expected);
  CHECK(integ.constraint_violation() < 1e-9);
}
