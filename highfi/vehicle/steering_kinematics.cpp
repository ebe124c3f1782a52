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

std::vector<SteerAngles> steering_kinematics(const FullVehicleSpec& spec, const std::vector<double>& arm_angles,
                                             double travel) {
  if (!spec.has_steering) throw InputError("steering kinematics: the vehicle has no steering");
  std::size_t steered = spec.axles.size();
  for (std::size_t k = 0; k < spec.axles.size(); ++k)
    if (spec.axles[k].steered && steered == spec.axles.size()) steered = k;
  if (steered == spec.axles.size()) throw InputError("steering kinematics: no axle is steered");
  FullVehicle v(spec, Vec3(0, 0, 10.0));  // in the air: no tire touches
  mb::MbSystem& s = v.system();
  s.bodies[std::size_t(v.chassis())].fixed = true;
  const PitmanArm& arm = v.steering();
  const mb::Joint hinge = s.joints[std::size_t(arm.revolute)];
  s.joints.erase(s.joints.begin() + arm.revolute);  // the arm is held instead
  mb::RigidBody& arm_body = s.bodies[std::size_t(arm.arm)];
  arm_body.fixed = true;
  const mb::RigidBody built_arm = arm_body;
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
  for (double angle : arm_angles) {
    const mb::Quat turn(Eigen::AngleAxisd(angle, arm.axis_chassis));
    arm_body.orientation = turn * built_arm.orientation;
    arm_body.position = pivot + turn * (built_arm.position - pivot);
    s.assemble();
    SteerAngles a;
    a.arm_angle = angle;
    a.left = steer_angle(s.bodies[std::size_t(left.spindle)]);
    a.right = steer_angle(s.bodies[std::size_t(right.spindle)]);
    a.ackermann_error = ackermann_error(a.left, a.right, track, wheelbase);
    out.push_back(a);
  }
  return out;
}

}  // namespace terracal::vehicle
