#include "highfi/vehicle/steering_kinematics.hpp"

#include <cmath>

#include "core/errors.hpp"

namespace terracal::vehicle {

double steer_angle(const mb::RigidBody& spindle) {
  const Vec3 axis = spindle.rotation() * Vec3::UnitY();
  const Vec3 heading = axis.cross(Vec3::UnitZ());
  return std::atan2(heading.y(), heading.x());
}

double ackermann_error(double left, double right, double track, double wheelbase) {
  if (std::abs(left) < 1e-9 && std::abs(right) < 1e-9) return 0;
  const bool to_left = left + right > 0;
  const double inner = to_left ? left : -right, outer = to_left ? right : -left;  // both > 0
  const double ideal = std::atan(1.0 / (1.0 / std::tan(inner) + track / wheelbase));
  return outer - ideal;
}

double predicted_turn_radius(double left, double right, double track, double wheelbase) {
  const double sign = left + right > 0 ? 1 : -1;  // a left turn: the left wheel is inside
  const double inner = std::abs(sign > 0 ? left : right), outer = std::abs(sign > 0 ? right : left);
  return 0.5 * ((wheelbase / std::tan(inner) + 0.5 * track) + (wheelbase / std::tan(outer) - 0.5 * track));
}

double steering_position(const FullVehicleSpec& spec, double input) {
  return spec.rack_steering ? input * spec.rack.max_travel() : -input * spec.steering.max_angle;
}

double steering_position(const FullVehicle& v) {
  return v.spec().rack_steering ? rack_travel(v.system(), v.rack()) : pitman_arm_angle(v.system(), v.steering());
}

std::vector<SteerAngles> steering_kinematics(const FullVehicleSpec& spec, const std::vector<double>& positions,
                                             double travel) {
  if (!spec.has_steering) throw InputError("steering kinematics: the vehicle has no steering");
  std::size_t steered = spec.axles.size();
  for (std::size_t k = 0; k < spec.axles.size(); ++k)
    if (spec.axles[k].steered && steered == spec.axles.size()) steered = k;
  if (steered == spec.axles.size()) throw InputError("steering kinematics: no axle is steered");
  FullVehicle v(spec, Vec3(0, 0, 10.0));  // in the air: no tire touches
  mb::MbSystem& s = v.system();
  s.bodies[std::size_t(v.chassis())].fixed = true;
  // The steering's moving part is held instead of its joint to the chassis.
  const int held_joint = spec.rack_steering ? v.rack().prismatic : v.steering().revolute;
  const mb::Joint hinge = s.joints[std::size_t(held_joint)];
  s.joints.erase(s.joints.begin() + held_joint);
  mb::RigidBody& moved = s.bodies[std::size_t(spec.rack_steering ? v.rack().rack : v.steering().arm)];
  moved.fixed = true;
  const mb::RigidBody built = moved;
  const Vec3 pivot = s.bodies[std::size_t(hinge.i)].point(hinge.si);
  // Each wheel centre held at its design height.
  for (const WishboneSide& w : v.corners()) {
    mb::Joint plane;
    plane.name = "height";
    plane.type = mb::JointType::point_on_plane;
    plane.i = v.chassis();
    plane.j = w.spindle;
    plane.si =
        s.bodies[std::size_t(w.spindle)].position - s.bodies[std::size_t(v.chassis())].position + Vec3(0, 0, travel);
    s.joints.push_back(plane);
  }
  s.index();
  const WishboneSide &left = v.corners()[2 * steered], &right = v.corners()[2 * steered + 1];
  const double track =
      (s.bodies[std::size_t(left.spindle)].position - s.bodies[std::size_t(right.spindle)].position).norm();
  const double wheelbase = spec.axles[steered].location.x() - spec.axles.back().location.x();
  std::vector<SteerAngles> out;
  for (double position : positions) {
    if (spec.rack_steering) {
      moved.position = built.position + position * v.rack().axis_chassis;
    } else {
      const mb::Quat turn(Eigen::AngleAxisd(position, v.steering().axis_chassis));
      moved.orientation = turn * built.orientation;
      moved.position = pivot + turn * (built.position - pivot);
    }
    s.assemble();
    SteerAngles a;
    a.position = position;
    a.left = steer_angle(s.bodies[std::size_t(left.spindle)]);
    a.right = steer_angle(s.bodies[std::size_t(right.spindle)]);
    a.ackermann_error = ackermann_error(a.left, a.right, track, wheelbase);
    out.push_back(a);
  }
  return out;
}

}  // namespace terracal::vehicle
