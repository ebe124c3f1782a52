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

}  // namespace terracal::test
