#pragma once
// Small mechanisms with known answers for the multibody tests.
#include "highfi/multibody/mb_system.hpp"

namespace terracal::test {

// A ground body (fixed) as body 0.
inline int add_ground(mb::MbSystem& s) {
  mb::RigidBody g;
  g.name = "ground";
  g.fixed = true;
  return s.add_body(g);
}

// A slender rod from a to b (mass m, radius r): centre between them, inertia of a solid cylinder,
// its body x axis along the rod.
inline int add_rod(mb::MbSystem& s, const std::string& name, const mb::Vec3& a, const mb::Vec3& b, double m,
                   double r = 0.01) {
  mb::RigidBody rod;
  rod.name = name;
  rod.mass = m;
  const double l = (b - a).norm();
  rod.position = 0.5 * (a + b);
  rod.orientation = mb::Quat::FromTwoVectors(mb::Vec3::UnitX(), (b - a).normalized());
  rod.inertia = mb::Vec3(0.5 * m * r * r, m * (3 * r * r + l * l) / 12, m * (3 * r * r + l * l) / 12).asDiagonal();
  return s.add_body(rod);
}

// Axes with z along `axis` (world), for joints placed with it.
inline mb::Mat3 axes_z(const mb::Vec3& axis) {
  return mb::Quat::FromTwoVectors(mb::Vec3::UnitZ(), axis.normalized()).toRotationMatrix();
}

// The crank-rocker four-bar of the tests and the benchmark: ground pivots 0.4 m apart, crank 0.1 m,
// coupler 0.447 m, rocker 0.3 m; hinges at the ground, ball joints on the coupler (its spin about its
// own axis is free and stays still: four hinges would constrain the out-of-plane motions twice). The
// crank starts upright at 10 rad/s. Returns the crank's body index.
inline int four_bar(mb::MbSystem& s) {
  using mb::Vec3;
  const int g = add_ground(s);
  const Vec3 a(0, 0, 0), b(0, 0, 0.1), c(0.4, 0, 0.3), d(0.4, 0, 0);
  const int crank = add_rod(s, "crank", a, b, 1.0);
  const int coupler = add_rod(s, "coupler", b, c, 2.0);
  const int rocker = add_rod(s, "rocker", d, c, 1.5);
  const mb::Mat3 y = axes_z(Vec3::UnitY());
  s.add_joint("A", mb::JointType::revolute, g, crank, a, y);
  s.add_joint("B", mb::JointType::spherical, crank, coupler, b);
  s.add_joint("C", mb::JointType::spherical, coupler, rocker, c);
  s.add_joint("D", mb::JointType::revolute, g, rocker, d, y);
  s.bodies[std::size_t(crank)].omega = Vec3(0, 10.0, 0);  // about the hinge (the rod's y is the world's)
  return crank;
}

}  // namespace terracal::test
