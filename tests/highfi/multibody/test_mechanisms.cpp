// Multibody core: closed loops. A slider-crank's slider follows the crank as its kinematics say; a
// four-bar's loop stays closed within 1e-8 over 100 s; a mass on a prismatic spring oscillates at
// sqrt(k/m); redundant joints are refused.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/errors.hpp"
#include "highfi/multibody/mb_integrator.hpp"
#include "tests/highfi/multibody/mb_test_systems.hpp"

using namespace terracal;
using namespace terracal::mb;

TEST_CASE("multibody: a slider-crank's slider is where the crank angle puts it", "[multibody]") {
  // Crank r hinged at the origin about y, a connecting rod l with a ball joint at each end, a slider on x.
  const double r = 0.1, l = 0.3;
  MbSystem s;
  const int g = test::add_ground(s);
  const Vec3 a(0, 0, 0), b(r * std::cos(0.3), 0, r * std::sin(0.3));
  const Vec3 c(b.x() + std::sqrt(l * l - b.z() * b.z()), 0, 0);
  const int crank = test::add_rod(s, "crank", a, b, 1.0);
  const int rod = test::add_rod(s, "rod", b, c, 0.5);
  RigidBody slider;
  slider.name = "slider";
  slider.mass = 0.8;
  slider.position = c;
  const int sl = s.add_body(slider);
  s.add_joint("main", JointType::revolute, g, crank, a, test::axes_z(Vec3::UnitY()));
  s.add_joint("crank pin", JointType::spherical, crank, rod, b);
  s.add_joint("wrist pin", JointType::spherical, rod, sl, c);
  s.add_joint("guide", JointType::prismatic, g, sl, c, test::axes_z(Vec3::UnitX()));
  s.bodies[std::size_t(crank)].omega = Vec3(0, -8.0, 0);  // about the hinge (the rod's y is the world's)
  MbIntegrator in(s, {1e-10, 1e-11});
  double worst = 0, turned = 0;
  for (double t = 0.01; t <= 5 + 1e-9; t += 0.01) {
    in.advance(t);
    const Vec3 pin = s.bodies[std::size_t(crank)].point(Vec3(r / 2, 0, 0));  // the crank's far end
    const double expected = pin.x() + std::sqrt(l * l - pin.z() * pin.z());
    worst = std::max(worst, std::abs(s.bodies[std::size_t(sl)].position.x() - expected));
    worst = std::max(worst, std::abs(s.bodies[std::size_t(sl)].position.z()));
    turned = std::max(turned, std::abs(std::atan2(pin.z(), pin.x())));
  }
  INFO("largest slider error " << worst << " m; crank reached " << turned << " rad");
  CHECK(turned > 3.0);  // the crank went round (the kinematics are checked over whole turns)
  CHECK(worst < 1e-8);
  CHECK(in.constraint_violation() < 1e-8);
}

TEST_CASE("multibody: a four-bar's loop stays closed within 1e-8 over 100 s", "[multibody]") {
  MbSystem s;
  const int crank = test::four_bar(s);
  MbIntegrator in(s, {1e-9, 1e-10});
  const double e0 = s.mechanical_energy();
  double violation = 0, turns = 0, last = 0;
  for (double t = 0.01; t <= 100 + 1e-9; t += 0.01) {
    in.advance(t);
    violation = std::max(violation, in.constraint_violation());
    const Vec3 tip = s.bodies[std::size_t(crank)].point(Vec3(0.05, 0, 0));
    const double angle = std::atan2(tip.x(), tip.z());
    if (last < -2.5 && angle > 2.5) turns += 1;
    if (last > 2.5 && angle < -2.5) turns += 1;
    last = angle;
  }
  INFO("largest constraint error " << violation << "; crank turns " << turns << "; energy " << e0 << " -> "
                                   << s.mechanical_energy() << " J; " << in.stats().steps << " steps");
  CHECK(turns >= 10);
  CHECK(violation < 1e-8);
  CHECK(std::abs(s.mechanical_energy() - e0) < 1e-4 * std::abs(e0) + 1e-4);
}

TEST_CASE("multibody: a mass on a prismatic spring oscillates at sqrt(k/m)", "[multibody]") {
  const double m = 4.0, k = 900.0;
  MbSystem s;
  s.gravity = Vec3::Zero();
  const int g = test::add_ground(s);
  RigidBody body;
  body.mass = m;
  body.position = Vec3(0.55, 0, 0);  // 0.05 m beyond the spring's rest length
  const int b = s.add_body(body);
  s.add_joint("slide", JointType::prismatic, g, b, body.position, test::axes_z(Vec3::UnitX()));
  SpringDamper spring;
  spring.i = g;
  spring.j = b;
  spring.rest_length = 0.5;
  spring.law = linear_law(k, 0.0);
  s.springs.push_back(spring);
  MbIntegrator in(s, {1e-11, 1e-12});
  const double omega = std::sqrt(k / m);
  double worst = 0;
  for (double t = 0.005; t <= 2 + 1e-9; t += 0.005) {
    in.advance(t);
    worst = std::max(worst, std::abs(s.bodies[std::size_t(b)].position.x() - (0.5 + 0.05 * std::cos(omega * t))));
  }
  INFO("largest deviation from 0.05 cos(sqrt(k/m) t): " << worst << " m");
  CHECK(worst < 1e-7);
}

TEST_CASE("multibody: joints that constrain a motion twice are refused", "[multibody]") {
  // A planar four-bar of four hinges constrains the out-of-plane motions twice.
  MbSystem s;
  const int g = test::add_ground(s);
  const Vec3 a(0, 0, 0), b(0, 0, 0.1), c(0.4, 0, 0.3), d(0.4, 0, 0);
  const int crank = test::add_rod(s, "crank", a, b, 1.0);
  const int coupler = test::add_rod(s, "coupler", b, c, 2.0);
  const int rocker = test::add_rod(s, "rocker", d, c, 1.5);
  const Mat3 y = test::axes_z(Vec3::UnitY());
  s.add_joint("A", JointType::revolute, g, crank, a, y);
  s.add_joint("B", JointType::revolute, crank, coupler, b, y);
  s.add_joint("C", JointType::revolute, coupler, rocker, c, y);
  s.add_joint("D", JointType::revolute, g, rocker, d, y);
  CHECK_THROWS_WITH(MbIntegrator(s), Catch::Contains("independent"));
}
