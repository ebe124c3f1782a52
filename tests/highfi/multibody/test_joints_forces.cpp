// Multibody core: the joints and force elements that the pendulum and mechanism tests leave out, each
// against an analytic answer. A distance joint makes a conical pendulum (constant height, period
// 2 pi sqrt(L cos a / g), tension m g / cos a); a point-on-line joint lets a spinning body slide down an
// incline at g sin(incline) and keep its spin; a universal joint between two shafts at an angle gives
// the Cardan speed ratio; a rotational spring-damper on a hinge oscillates at sqrt(k/I) and decays as
// exp(-c t / (2 I)); a bushing deflects m g / k under a weight and turns at sqrt(k/I) about its soft
// axis; a tabulated law that is linear moves a body as the linear law does, also past the table's ends.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "highfi/multibody/mb_integrator.hpp"
#include "tests/highfi/multibody/mb_test_systems.hpp"

using namespace terracal;
using namespace terracal::mb;

namespace {
constexpr double g0 = 9.81;

// Times at which value() changes sign, sampled every dt from the integrator's time to t_end, linearly
// interpolated between samples. sample() is called after each step (for other measurements).
template <class Value, class Sample>
std::vector<double> sign_changes(MbIntegrator& in, Value value, Sample sample, double t_end, double dt) {
  std::vector<double> out;
  const double start = in.time();
  double t0 = start, x0 = value();
  for (int n = 1;; ++n) {
    const double t = start + n * dt;
    if (t > t_end + 1e-12) break;
    in.advance(t);
    sample(t);
    const double x = value();
    if ((x0 < 0) != (x < 0)) out.push_back(t0 + (t - t0) * x0 / (x0 - x));
    t0 = t, x0 = x;
  }
  return out;
}

// The period from the sign changes of an oscillation (two per period), over as many as there are.
double period_from(const std::vector<double>& cross) {
  return 2 * (cross.back() - cross.front()) / double(cross.size() - 1);
}

// A turn by angle about z.
Mat3 rot_z(double angle) { return Eigen::AngleAxisd(angle, Vec3::UnitZ()).toRotationMatrix(); }

// A rod (m 2 kg, 0.5 m) hinged at one end about a tilted axis normal to it, gravity off, with a
// rotational spring-damper about the hinge whose zero is theta0 behind the rod's starting angle.
MbSystem hinged_rod(double k, double c, double theta0) {
  MbSystem s;
  s.gravity = Vec3::Zero();
  const int g = test::add_ground(s);
  const Vec3 axis = Vec3(0.3, 1, 0.2).normalized();
  const int rod = test::add_rod(s, "rod", Vec3::Zero(), 0.5 * axis.cross(Vec3::UnitZ()).normalized(), 2.0);
  const Mat3 hinge = test::axes_z(axis);
  s.add_joint("hinge", JointType::revolute, g, rod, Vec3::Zero(), hinge);
  RotationalSpringDamper spring;
  spring.name = "spring";
  spring.i = g;
  spring.j = rod;
  spring.frame_i = hinge * rot_z(-theta0);
  spring.frame_j = s.bodies[std::size_t(rod)].rotation().transpose() * hinge;
  spring.law = linear_law(k, c);
  s.rotational_springs.push_back(spring);
  return s;
}
}  // namespace

TEST_CASE("multibody: a distance joint makes a conical pendulum of constant height and period 2 pi sqrt(L cos a/g)",
          "[multibody]") {
  // A body tied by its centre to a ground point: the joint's row has no part on the body's rotation,
  // so the centre moves as a point mass on a sphere and the body's spin (about a principal axis) stays.
  const double l = 1.2, a = 40.0 * M_PI / 180, m = 2.0;
  const double radius = l * std::sin(a), height = l * std::cos(a);
  const double speed = std::sqrt(g0 * l * std::sin(a) * std::tan(a));
  const double period = 2 * M_PI * std::sqrt(l * std::cos(a) / g0);
  MbSystem s;
  s.gravity = Vec3(0, 0, -g0);
  const int g = test::add_ground(s);
  RigidBody bob;
  bob.name = "bob";
  bob.mass = m;
  bob.inertia = Vec3(0.01, 0.02, 0.03).asDiagonal();
  bob.position = Vec3(radius, 0, -height);
  bob.orientation = Quat(Eigen::AngleAxisd(0.3, Vec3(1, 2, 0).normalized()));
  bob.velocity = Vec3(0, speed, 0);
  bob.omega = Vec3(0, 0, 7.0);
  const int b = s.add_body(bob);
  s.add_joint("string", JointType::distance, g, b, Vec3::Zero(), Mat3::Identity(), bob.position);
  REQUIRE(s.joints[0].length == Approx(l).epsilon(1e-15));
  MbIntegrator in(s, {1e-11, 1e-12});
  const RigidBody& body = s.bodies[std::size_t(b)];
  double height_error = 0, tension_error = 0, spin_error = 0;
  const std::vector<double> cross = sign_changes(
      in, [&] { return body.position.y(); },
      [&](double) {
        height_error = std::max(height_error, std::abs(body.position.z() + height));
        // The string pulls the body towards the pivot with m g / cos a.
        const Vec3 expected = -body.position.normalized() * m * g0 / std::cos(a);
        tension_error = std::max(tension_error, (in.reaction(0, b).force - expected).norm() / expected.norm());
        spin_error = std::max(spin_error, (body.omega - Vec3(0, 0, 7.0)).norm());
      },
      4.2 * period, 1e-3);
  REQUIRE(cross.size() >= 8);  // y changes sign twice a turn
  const double measured = period_from(cross);
  INFO("period " << measured << " s, 2 pi sqrt(L cos a/g) " << period << " s, relative error "
                 << std::abs(measured - period) / period << "; largest height error " << height_error
                 << " m; tension error " << tension_error << " (relative); spin error " << spin_error << " rad/s");
  CHECK(std::abs(measured - period) / period < 1e-6);
  CHECK(height_error < 1e-8);
  CHECK(tension_error < 1e-7);
  CHECK(spin_error < 1e-9);
  CHECK(in.constraint_violation() < 1e-8);
}

TEST_CASE("multibody: a body on a point-on-line joint slides down the incline at g sin(incline) and keeps its spin",
          "[multibody]") {
  // The body's centre is held on a straight line of the ground, at 30 degrees to the horizontal and
  // not in a coordinate plane. Its inertia is spherical, so a spin about any axis stays as it is.
  const double incline = 30.0 * M_PI / 180, heading = 25.0 * M_PI / 180, m = 3.0;
  const Vec3 down(std::cos(incline) * std::cos(heading), std::cos(incline) * std::sin(heading), -std::sin(incline));
  const Vec3 w0 = Vec3(1.0, -2.0, 0.5) * 4.0;  // rad/s, body frame
  MbSystem s;
  s.gravity = Vec3(0, 0, -g0);
  const int g = test::add_ground(s);
  RigidBody puck;
  puck.name = "puck";
  puck.mass = m;
  puck.inertia = 0.25 * Mat3::Identity();
  puck.position = Vec3(0.4, -0.3, 1.0);
  puck.orientation = Quat(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
  puck.omega = w0;
  const int b = s.add_body(puck);
  s.add_joint("rail", JointType::point_on_line, g, b, puck.position, test::axes_z(down));
  MbIntegrator in(s, {1e-11, 1e-12});
  const RigidBody& body = s.bodies[std::size_t(b)];
  const double accel = g0 * std::sin(incline);
  // The rail holds the part of the weight across it: m g cos(incline), pushing up off the line.
  const Vec3 g_across = s.gravity - s.gravity.dot(down) * down;
  double position_error = 0, spin_error = 0, attitude_error = 0, normal_error = 0;
  for (double t = 0.01; t <= 2.0 + 1e-9; t += 0.01) {
    in.advance(t);
    const Vec3 expected = puck.position + 0.5 * accel * t * t * down;
    position_error = std::max(position_error, (body.position - expected).norm());
    spin_error = std::max(spin_error, (body.omega - w0).norm());
    const Quat turned = puck.orientation * Quat(Eigen::AngleAxisd(w0.norm() * t, w0.normalized()));
    attitude_error = std::max(attitude_error, body.orientation.angularDistance(turned));
    normal_error = std::max(normal_error, (in.reaction(0, b).force + m * g_across).norm() / (m * g_across.norm()));
  }
  INFO("largest distance from p0 + g sin(incline) t^2/2 along the line "
       << position_error << " m; spin error " << spin_error << " rad/s; attitude error " << attitude_error
       << " rad; normal force " << normal_error << " (relative)");
  CHECK(position_error < 1e-8);
  CHECK(spin_error < 1e-9);
  CHECK(attitude_error < 1e-8);
  CHECK(normal_error < 1e-8);
  CHECK(in.constraint_violation() < 1e-8);
}

TEST_CASE("multibody: a universal joint between shafts at an angle gives the Cardan speed ratio", "[multibody]") {
  // The input shaft along world x, hinged to the ground; the output shaft at beta = 30 degrees to it in
  // the xy plane; the cross at the origin, where the two shafts meet. Joint rows, non-redundant:
  //   input bearing, revolute (ground, input): 5 rows, leaving the input its spin about x;
  //   cross, universal (input, output): 4 rows, the output's end at the origin (held by the input's
  //     bearing, since the origin is on its axis) and the output's arm normal to the input's arm;
  //   output bearing, point-on-line (ground, output) at the output's far end along its axis: 2 rows.
  // The output's origin fixed (3) and its far end held on its axis (2) leave it the spin about its
  // axis, which the cross (1) ties to the input's: 11 independent rows on 12 velocities, one degree of
  // freedom. A second revolute for the output would constrain its axis twice (14 rows, rank 11).
  // The cross's arms: x on the input, along world z (normal to the input shaft), and y on the output,
  // (-sin beta, cos beta, 0) (normal to the output shaft and to the input's arm).
  const double beta = 30.0 * M_PI / 180, w10 = 10.0;
  const Vec3 e1 = Vec3::UnitX(), e2(std::cos(beta), std::sin(beta), 0);
  MbSystem s;
  s.gravity = Vec3::Zero();
  const int g = test::add_ground(s);
  const int input = test::add_rod(s, "input", -0.6 * e1, Vec3::Zero(), 5.0, 0.05);
  const int output = test::add_rod(s, "output", Vec3::Zero(), 0.5 * e2, 1.0, 0.05);
  const double i_out = s.bodies[std::size_t(output)].inertia(0, 0);
  s.bodies[std::size_t(input)].inertia(0, 0) = 1e6 * i_out;  // a flywheel: its speed hardly varies
  Mat3 cross;
  cross.col(0) = Vec3::UnitZ();
  cross.col(1) = Vec3(-std::sin(beta), std::cos(beta), 0);
  cross.col(2) = cross.col(0).cross(cross.col(1));
  s.add_joint("input bearing", JointType::revolute, g, input, -0.3 * e1, test::axes_z(e1));
  s.add_joint("cross", JointType::universal, input, output, Vec3::Zero(), cross);
  {
    MbSystem twice = s;  // the output hinged too: refused
    twice.add_joint("output hinge", JointType::revolute, g, output, 0.25 * e2, test::axes_z(e2));
    CHECK_THROWS_WITH(MbIntegrator(twice), Catch::Contains("independent"));
  }
  s.add_joint("output bearing", JointType::point_on_line, g, output, 0.5 * e2, test::axes_z(e2));
  // The rods' body x is along the shaft. The input's arm starts normal to the shafts' plane, where
  // the output turns at w1 cos(beta).
  s.bodies[std::size_t(input)].omega = Vec3(w10, 0, 0);
  s.bodies[std::size_t(output)].omega = Vec3(w10 * std::cos(beta), 0, 0);
  MbIntegrator in(s, {1e-10, 1e-11});
  // The energy the output trades with the flywheel: measured against the output's own.
  const double e0 = s.mechanical_energy();
  const double e_out = 0.5 * i_out * std::pow(w10 * std::cos(beta), 2);
  const RigidBody &in_shaft = s.bodies[std::size_t(input)], &out_shaft = s.bodies[std::size_t(output)];
  const Vec3 arm = s.joints[1].frame_i.col(0);  // the input's arm, input body frame
  const double s2 = std::sin(beta) * std::sin(beta);
  double kinematic = 0, flywheel = 0, w1_change = 0, violation = 0, energy = 0, turned = 0, lowest = 10, highest = 0;
  double last = M_PI / 2;
  for (double t = 0.005; t <= 2.0 + 1e-9; t += 0.005) {
    in.advance(t);
    const Vec3 u1 = in_shaft.rotation() * arm;
    const double theta1 = std::atan2(u1.z(), u1.y());  // from the shafts' plane, about x
    const double w1 = e1.dot(in_shaft.rotation() * in_shaft.omega);
    const double w2 = e2.dot(out_shaft.rotation() * out_shaft.omega);
    const double ratio = std::cos(beta) / (1 - s2 * std::cos(theta1) * std::cos(theta1));
    kinematic = std::max(kinematic, std::abs(w2 - w1 * ratio) / w10);  // with the input's speed now
    flywheel = std::max(flywheel, std::abs(w2 - w10 * ratio) / w10);   // with its initial speed
    w1_change = std::max(w1_change, std::abs(w1 - w10) / w10);
    violation = std::max(violation, in.constraint_violation());
    energy = std::max(energy, std::abs(s.mechanical_energy() - e0) / e_out);
    turned += std::remainder(theta1 - last, 2 * M_PI);
    last = theta1;
    lowest = std::min(lowest, w2 / w1), highest = std::max(highest, w2 / w1);
  }
  INFO("largest |w2 - w1 cos b/(1 - sin^2 b cos^2 theta1)|/w1: "
       << kinematic << " with w1 now, " << flywheel << " with w1 at the start; input speed change " << w1_change
       << "; w2/w1 from " << lowest << " to " << highest << "; input turned " << turned << " rad; constraint error "
       << violation << "; energy change " << energy << " of the output's");
  CHECK(turned > 3 * 2 * M_PI);
  // The ratio sweeps cos(beta) .. 1/cos(beta) (sampled, so only nearly to the ends).
  CHECK(lowest < std::cos(beta) + 1e-3);
  CHECK(highest > 1 / std::cos(beta) - 1e-3);
  CHECK(kinematic < 1e-8);
  // Energy: I1 w1^2 + I2 w2^2 is constant, so w1 changes by at most
  // (I2/I1) (1/cos^2 b - cos^2 b) / 2 = 2.9e-7 of itself.
  CHECK(w1_change < 1e-6);
  CHECK(flywheel < 1e-6);
  CHECK(energy < 1e-6);
  CHECK(violation < 1e-8);
}

TEST_CASE("multibody: a rotational spring-damper on a hinge oscillates at sqrt(k/I) and decays as exp(-c t/(2 I))",
          "[multibody]") {
  // theta(t) = theta0 e^(-s t) (cos(wd t) + s/wd sin(wd t)), s = c/(2 I), wd = sqrt(k/I - s^2), I the
  // rod's inertia about the hinge (about its centre plus m (l/2)^2).
  const double k = 40.0, theta0 = 0.3, m = 2.0, len = 0.5, r = 0.01;
  const double inertia = m * (3 * r * r + len * len) / 12 + m * 0.25 * len * len;
  const double wn = std::sqrt(k / inertia);
  const bool damped = GENERATE(false, true);
  const double c = damped ? 2 * 0.05 * inertia * wn : 0.0;  // 5 % of critical
  const double sigma = c / (2 * inertia), wd = std::sqrt(wn * wn - sigma * sigma), td = 2 * M_PI / wd;
  const auto exact = [&](double t) {
    return theta0 * std::exp(-sigma * t) * (std::cos(wd * t) + sigma / wd * std::sin(wd * t));
  };
  MbSystem s = hinged_rod(k, c, theta0);
  REQUIRE(s.rotational_springs[0].angle(s.bodies) == Approx(theta0).epsilon(1e-14));
  // The angle measured from the rod's direction (its body x) about the hinge, from the spring's zero.
  const RigidBody& rod = s.bodies[1];
  const Vec3 axis = rod.rotation() * s.joints[0].frame_j.col(2), start = rod.rotation().col(0);
  const auto angle = [&] {
    const Vec3 now = rod.rotation().col(0);
    return theta0 + std::atan2(start.cross(now).dot(axis), start.dot(now));
  };
  MbIntegrator in(s, {1e-11, 1e-12});
  double trajectory = 0;
  const int periods = 6;
  const std::vector<double> cross = sign_changes(
      in, angle, [&](double t) { trajectory = std::max(trajectory, std::abs(angle() - exact(t)) / theta0); },
      periods * td, 2.5e-4);
  REQUIRE(cross.size() >= 2 * periods - 1);
  const double measured = period_from(cross);
  // At whole damped periods the angle is theta0 e^(-s n Td): the decay rate from it.
  in.advance(periods * td);
  const double decay = damped ? -std::log(angle() / theta0) / (periods * td) : 0.0;
  INFO((damped ? "damped" : "undamped") << ": period " << measured << " s, 2 pi/wd " << td << " s, relative error "
                                        << std::abs(measured - td) / td << "; decay rate " << decay << " 1/s, c/(2I) "
                                        << sigma << "; largest |theta - exact| / theta0 " << trajectory);
  CHECK(std::abs(measured - td) / td < 1e-7);
  CHECK(trajectory < 1e-8);
  if (damped) CHECK(std::abs(decay - sigma) / sigma < 1e-7);
  CHECK(in.constraint_violation() < 1e-8);
}

TEST_CASE("multibody: a bushing deflects m g / k under a body's weight and turns at sqrt(k/I) about its soft axis",
          "[multibody]") {
  // A body held to the ground only by a bushing at its centre, in a frame Q tilted off the world's
  // axes. Stiff (1e6 N/m, 1e4 N m/rad) but for one soft direction, critically damped.
  const double m = 2.0;
  const Mat3 inertia = Vec3(0.1, 0.2, 0.3).asDiagonal();
  const Mat3 q = Eigen::AngleAxisd(0.5, Vec3(1, -1, 2).normalized()).toRotationMatrix();
  const Vec3 p0(0.3, 0.1, 1.0);
  MbSystem s;
  const int g = test::add_ground(s);
  RigidBody block;
  block.name = "block";
  block.mass = m;
  block.inertia = inertia;
  block.position = p0;
  SECTION("along the soft axis, the weight deflects it by m g / k") {
    const double k = 2000.0;
    s.gravity = -g0 * q.col(2);  // along the bushing's z
    block.orientation = Quat(Eigen::AngleAxisd(0.8, Vec3(2, 1, -1).normalized()));
    const int b = s.add_body(block);
    Bushing bush;
    bush.i = g;
    bush.j = b;
    bush.si = p0;
    bush.frame_i = q;
    bush.frame_j = block.rotation().transpose() * q;
    bush.k_lin = Vec3(1e6, 1e6, k);
    bush.c_lin = 2 * (bush.k_lin * m).cwiseSqrt();  // critical
    bush.k_rot = Vec3(1e4, 1e4, 1e4);
    bush.c_rot = Vec3(20, 20, 20);
    s.bushings.push_back(bush);
    MbIntegrator in(s, {1e-11, 1e-12});
    in.advance(1.5);  // 47 times 1/sqrt(k/m): (1 + w t) e^(-w t) ~ 1e-19
    const Vec3 moved = s.bodies[std::size_t(b)].position - p0;
    const double along = -moved.dot(q.col(2)), expected = m * g0 / k;
    const double across = (moved + along * q.col(2)).norm();
    const double turned = s.bodies[std::size_t(b)].orientation.angularDistance(block.orientation);
    INFO("deflection " << along << " m, m g / k " << expected << " m, relative error "
                       << std::abs(along - expected) / expected << "; across " << across << " m; turned " << turned
                       << " rad; speed " << s.bodies[std::size_t(b)].velocity.norm() << " m/s");
    CHECK(std::abs(along - expected) / expected < 1e-9);
    CHECK(across < 1e-12);
    CHECK(turned < 1e-12);
  }
  SECTION("about the soft axis, it turns at sqrt(k/I)") {
    // The body's axes are the bushing's, so the soft axis is its principal z: a turn about it alone.
    // The bushing's zero is theta0 behind the body, so the turn is theta0 cos(sqrt(k/I) t) (the
    // rotation vector's law is exact for a turn about one axis, even a large one).
    const double k = 30.0, theta0 = 0.6, omega = std::sqrt(k / inertia(2, 2));
    s.gravity = Vec3::Zero();
    block.orientation = Quat(q);
    const int b = s.add_body(block);
    Bushing bush;
    bush.i = g;
    bush.j = b;
    bush.si = p0;
    bush.frame_i = q;
    bush.frame_j = rot_z(theta0);
    bush.k_lin = Vec3(1e6, 1e6, 1e6);
    bush.k_rot = Vec3(1e4, 1e4, k);
    s.bushings.push_back(bush);
    MbIntegrator in(s, {1e-11, 1e-12});
    const RigidBody& body = s.bodies[std::size_t(b)];
    const auto deflection = [&] {
      const Eigen::AngleAxisd rel(q.transpose() * body.rotation() * bush.frame_j);
      return Vec3(rel.angle() * rel.axis());
    };
    REQUIRE(deflection().z() == Approx(theta0).epsilon(1e-14));
    double trajectory = 0, off_axis = 0, drift = 0;
    const double period = 2 * M_PI / omega;
    const std::vector<double> cross = sign_changes(
        in, [&] { return deflection().z(); },
        [&](double t) {
          trajectory = std::max(trajectory, std::abs(deflection().z() - theta0 * std::cos(omega * t)) / theta0);
          off_axis = std::max(off_axis, deflection().head<2>().norm());
          drift = std::max(drift, (body.position - p0).norm());
        },
        4.2 * period, 2.5e-4);
    REQUIRE(cross.size() >= 8);
    const double measured = period_from(cross);
    INFO("period " << measured << " s, 2 pi sqrt(I/k) " << period << " s, relative error "
                   << std::abs(measured - period) / period << "; largest |theta - theta0 cos(wt)| / theta0 "
                   << trajectory << "; off the axis " << off_axis << " rad; centre moved " << drift << " m");
    CHECK(std::abs(measured - period) / period < 1e-7);
    CHECK(trajectory < 1e-7);
    CHECK(off_axis < 1e-12);
    CHECK(drift < 1e-12);
  }
}

TEST_CASE("multibody: a tabulated law that is linear moves a spring-damper as the linear law does, past its ends too",
          "[multibody]") {
  SECTION("the table is piecewise linear and extended with its end segments' slopes") {
    // Slopes 1500, 1000, 2000 N/m; damper 5 N s/m.
    const ForceLaw law = table_law({-0.02, 0, 0.01, 0.03}, {-30, 0, 10, 50}, {-1, 2}, {-5, 10});
    CHECK(law(0.0, 0.0) == Approx(0.0).margin(1e-12));
    CHECK(law(0.005, 0.0) == Approx(5.0).epsilon(1e-14));
    CHECK(law(-0.01, 0.0) == Approx(-15.0).epsilon(1e-14));
    CHECK(law(0.02, 0.0) == Approx(30.0).epsilon(1e-14));
    CHECK(law(0.05, 0.0) == Approx(90.0).epsilon(1e-14));    // past the top: 50 + 2000 (0.02)
    CHECK(law(-0.05, 0.0) == Approx(-75.0).epsilon(1e-14));  // past the bottom: -30 + 1500 (-0.03)
    CHECK(law(0.0, 3.0) == Approx(15.0).epsilon(1e-14));     // past the rate table's ends
    CHECK(law(0.0, -2.0) == Approx(-10.0).epsilon(1e-14));
    CHECK(law(0.05, -2.0) == Approx(80.0).epsilon(1e-14));  // the two parts add
  }
  SECTION("a mass on a prismatic spring-damper: the same motion as linear_law(k, c)") {
    // m 4 kg, k 900 N/m, c 6 N s/m, released 0.05 m out: the deflection reaches +-0.05 m and the rate
    // +-0.7 m/s, past the tables' ends (-0.02 .. 0.03 m, -0.3 .. 0.4 m/s), unevenly spaced.
    const double m = 4.0, k = 900.0, c = 6.0;
    const auto build = [&](ForceLaw law) {
      MbSystem s;
      s.gravity = Vec3::Zero();
      const int g = test::add_ground(s);
      RigidBody body;
      body.mass = m;
      body.position = Vec3(0.55, 0, 0);
      const int b = s.add_body(body);
      s.add_joint("slide", JointType::prismatic, g, b, body.position, test::axes_z(Vec3::UnitX()));
      SpringDamper spring;
      spring.i = g;
      spring.j = b;
      spring.rest_length = 0.5;
      spring.law = std::move(law);
      s.springs.push_back(spring);
      return s;
    };
    const std::vector<double> defl{-0.02, -0.005, 0.01, 0.03}, rate{-0.3, 0.4};
    std::vector<double> force, damper;
    for (double x : defl) force.push_back(k * x);
    for (double v : rate) damper.push_back(c * v);
    MbSystem linear = build(linear_law(k, c)), table = build(table_law(defl, force, rate, damper));
    MbIntegrator in_linear(linear, {1e-11, 1e-12}), in_table(table, {1e-11, 1e-12});
    // The linear motion: x = 0.05 e^(-s t) (cos(wd t) + s/wd sin(wd t)).
    const double sigma = c / (2 * m), wd = std::sqrt(k / m - sigma * sigma);
    double apart = 0, from_exact = 0, lowest = 0, highest = 0, fastest = 0, slowest = 0;
    for (double t = 0.005; t <= 2.0 + 1e-9; t += 0.005) {
      in_linear.advance(t);
      in_table.advance(t);
      const double x = table.bodies[1].position.x() - 0.5, v = table.bodies[1].velocity.x();
      apart = std::max(apart, std::abs(x - (linear.bodies[1].position.x() - 0.5)));
      const double exact = 0.05 * std::exp(-sigma * t) * (std::cos(wd * t) + sigma / wd * std::sin(wd * t));
      from_exact = std::max(from_exact, std::abs(x - exact));
      lowest = std::min(lowest, x), highest = std::max(highest, x);
      slowest = std::min(slowest, v), fastest = std::max(fastest, v);
    }
    INFO("largest difference table - linear " << apart << " m; table - exact " << from_exact << " m; deflection "
                                              << lowest << " .. " << highest << " m; rate " << slowest << " .. "
                                              << fastest << " m/s");
    CHECK(lowest < -0.03);
    CHECK(highest > 0.04);
    CHECK(slowest < -0.5);
    CHECK(fastest > 0.5);
    CHECK(apart < 1e-9);
    CHECK(from_exact < 1e-8);
  }
}
