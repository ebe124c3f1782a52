#include "highfi/vehicle/suspension_kinematics.hpp"

#include <cmath>

namespace terracal::vehicle {

WheelAlignment alignment(const Vec3& axis, double side) {
  const Vec3 out = side * axis.normalized();  // the wheel's outward normal
  WheelAlignment a;
  a.camber = std::asin(-out.z());                  // the top outwards tilts the outward normal down
  a.toe = std::atan2(out.x(), std::abs(out.y()));  // toe-in turns the outward normal forwards
  return a;
}

std::vector<WheelAlignment> double_wishbone_kinematics(const DoubleWishboneSpec& spec,
                                                       const std::vector<double>& travels, double side) {
  mb::MbSystem s;
  s.gravity = Vec3::Zero();
  mb::RigidBody chassis;
  chassis.name = "chassis";
  chassis.fixed = true;
  const int c = s.add_body(chassis);
  const WishboneSide w = build_double_wishbone(s, spec, c, c, Vec3::Zero(), Vec3::Zero(), side);
  const Vec3 design = s.bodies[std::size_t(w.spindle)].position;
  std::vector<WheelAlignment> out;
  for (double travel : travels) {
    // The wheel centre held on the horizontal plane at the design height plus the travel.
    mb::Joint held;
    held.name = "travel";
    held.type = mb::JointType::point_on_plane;
    held.i = c;
    held.j = w.spindle;
    held.si = design + Vec3(0, 0, travel);  // the chassis frame is the world's here
    held.sj = Vec3::Zero();                 // the spindle's centre
    s.joints.push_back(held);
    s.assemble();
    s.joints.pop_back();
    const mb::RigidBody& sp = s.bodies[std::size_t(w.spindle)];
    WheelAlignment a = alignment(sp.rotation() * Vec3::UnitY(), side);
    a.travel = sp.position.z() - design.z();
    a.lateral = side * (sp.position.y() - design.y());
    out.push_back(a);
  }
  return out;
}

}  // namespace terracal::vehicle
