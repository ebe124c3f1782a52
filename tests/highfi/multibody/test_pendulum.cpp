// Multibody core: a large-amplitude pendulum's period against the elliptic integral, the energy of a
// double pendulum over 100 s, and the reactions of bodies at rest.
#include <catch2/catch.hpp>

#include <cmath>

#include <gsl/gsl_sf_ellint.h>

#include "highfi/multibody/mb_integrator.hpp"
#include "tests/highfi/multibody/mb_test_systems.hpp"

using namespace terracal;
using namespace terracal::mb;

namespace {
// A rod of length l hinged at the origin about y, released at angle theta0 from hanging straight down.
MbSystem pendulum(double l, double theta0) {
  MbSystem s;
  const int g = test::add_ground(s);
  const Vec3 tip(l * std::sin(theta0), 0, -l * std::cos(theta0));
  const int rod = test::add_rod(s, "rod", Vec3::Zero(), tip, 2.0);
  s.add_joint("hinge", JointType::revolute, g, rod, Vec3::Zero(), test::axes_z(Vec3::UnitY()));
  return s;
}

// Times at which x(t) changes sign, linearly interpolated between samples.
std::vector<double> sign_changes(MbIntegrator& in, const MbSystem& s, int body, double t_end, double dt) {
  std::vector<double> out;
  double t0 = in.time(), x0 = s.bodies[std::size_t(body)].position.x();
  for (double t = t0 + dt; t <= t_end + 1e-12; t += dt) {
    in.advance(t);
    const double x = s.bodies[std::size_t(body)].position.x();
    if ((x0 < 0) != (x < 0)) out.push_back(t0 + (t - t0) * x0 / (x0 - x));
    t0 = t, x0 = x;
  }
  return out;
}
}  // namespace

TEST_CASE("multibody: a pendulum released at 150 degrees swings with the elliptic integral's period", "[multibody]") {
  const double l = 1.0, theta0 = 150.0 * M_PI / 180;
  MbSystem s = pendulum(l, theta0);
  const RigidBody& rod = s.bodies[1];
  const double d = 0.5 * l, ip = rod.inertia(1, 1) + rod.mass * d * d;  // about the hinge
  const double period =
      4 * std::sqrt(ip / (rod.mass * 9.81 * d)) * gsl_sf_ellint_Kcomp(std::sin(theta0 / 2), GSL_PREC_DOUBLE);
  MbIntegrator in(s, {1e-11, 1e-12});
  const std::vector<double> cross = sign_changes(in, s, 1, 4.2 * period, 1e-3);
  REQUIRE(cross.size() >= 7);  // two crossings of the vertical per period
  const double measured = (cross[6] - cross[0]) / 3;
  INFO("period " << measured << " s, elliptic integral " << period << " s, relative error "
                 << std::abs(measured - period) / period);
  CHECK(std::abs(measured - period) / period < 1e-6);
  CHECK(in.constraint_violation() < 1e-8);
}

TEST_CASE("multibody: a double pendulum keeps its energy within 1e-6 over 100 s", "[multibody]") {
  MbSystem s;
  const int g = test::add_ground(s);
  const Vec3 a(0, 0, 0), b(0.6, 0.2, -0.5), c(1.0, -0.3, -0.2);
  const int r1 = test::add_rod(s, "upper", a, b, 1.5), r2 = test::add_rod(s, "lower", b, c, 1.0);
  s.add_joint("top", JointType::spherical, g, r1, a);
  s.add_joint("middle", JointType::revolute, r1, r2, b, test::axes_z(Vec3(0.3, 1, 0.2)));
  s.bodies[std::size_t(r2)].omega = Vec3(0, 0, 2.0);  // a twist the assembly projects onto the joints
  MbIntegrator in(s, {1e-11, 1e-12});
  // Energy measured from both rods hanging straight down, so that it is a positive scale.
  const double lowest = -9.81 * (1.5 * (-0.5 * (b - a).norm()) + 1.0 * (-(b - a).norm() - 0.5 * (c - b).norm()));
  const double e0 = s.mechanical_energy() + lowest;
  REQUIRE(e0 > 1.0);
  double worst = 0, violation = 0;
  for (double t = 0.1; t <= 100 + 1e-9; t += 0.1) {
    in.advance(t);
    worst = std::max(worst, std::abs(s.mechanical_energy() + lowest - e0) / e0);
    violation = std::max(violation, in.constraint_violation());
  }
  INFO("energy " << e0 << " J, largest relative change " << worst << ", largest constraint error " << violation);
  CHECK(worst < 1e-6);
  CHECK(violation < 1e-8);
}

TEST_CASE("multibody: the reactions of bodies at rest carry their weight", "[multibody]") {
  SECTION("a hanging pendulum's hinge carries the rod's weight, upwards") {
    MbSystem s = pendulum(0.8, 0.0);
    MbIntegrator in(s);
    in.advance(1.0);
    const Wrench w = in.reaction(0, 1);
    INFO("reaction " << w.force.transpose() << " N, torque " << w.torque.transpose());
    CHECK(std::abs(w.force.z() - 2.0 * 9.81) < 1e-9 * 2.0 * 9.81);
    CHECK(w.force.head<2>().norm() < 1e-9);
    CHECK(s.bodies[1].velocity.norm() < 1e-12);
  }
  SECTION("a box welded to the ground away from its centre: its weight and the moment of it") {
    MbSystem s;
    const int g = test::add_ground(s);
    RigidBody box;
    box.mass = 30;
    box.position = Vec3(1, 2, 0.5);
    box.orientation = Quat(Eigen::AngleAxisd(0.4, Vec3(1, 1, 0).normalized()));
    const int b = s.add_body(box);
    s.add_joint("weld", JointType::fixed, g, b, Vec3(0.7, 2, 0.5), test::axes_z(Vec3(0, 1, 1)));
    MbIntegrator in(s);
    in.advance(2.0);
    const Wrench w = in.reaction(0, b);
    // At rest, gravity acts at the centre: the weld holds 30 g up and no moment about the centre.
    INFO("force " << w.force.transpose() << ", torque " << w.torque.transpose());
    CHECK((w.force - Vec3(0, 0, 30 * 9.81)).norm() < 1e-9 * 30 * 9.81);
    CHECK(w.torque.norm() < 1e-8);
    CHECK(s.bodies[std::size_t(b)].position.isApprox(box.position, 1e-12));
  }
}
