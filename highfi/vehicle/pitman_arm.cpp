#include "highfi/vehicle/pitman_arm.hpp"

#include "highfi/vehicle/vehicle_json.hpp"

#include <cmath>

#include <fmt/format.h>

namespace terracal::vehicle {

PitmanArmSpec read_pitman_arm(JsonObject o) {
  PitmanArmSpec s;
  o.string_or("template", "pitman_arm", {"pitman_arm"});
  s.name = read_name(o, s.name);
  if (o.has("source")) o.raw("source");
  s.link = read_part(o.object("link"));
  s.arm = read_part(o.object("arm"));
  {
    JsonObject r = o.object("revolute");
    s.revolute_point = read_point(r, "point");
    s.revolute_axis = read_direction(r, "axis");
    s.max_angle = r.number("max_angle", 0, M_PI / 2, true);
    r.finish();
  }
  {
    JsonObject u = o.object("universal");
    s.universal_point = read_point(u, "point");
    s.universal_axis_arm = read_direction(u, "axis_arm");
    s.universal_axis_link = read_direction(u, "axis_link");
    if (std::abs(s.universal_axis_arm.dot(s.universal_axis_link)) > 1e-6)
      u.fail("axis_link", "is not perpendicular to axis_arm; expected the cross's two axes at right angles");
    u.finish();
  }
  {
    JsonObject i = o.object("idler");
    s.idler_chassis = read_point(i, "chassis");
    s.idler_link = read_point(i, "link");
    s.idler_axis = read_direction(i, "axis");
    i.finish();
  }
  s.location = read_point(o, "location");
  s.orientation = read_orientation(o);
  read_servo(o, s.servo_stiffness, s.servo_damping);
  o.finish();
  return s;
}

PitmanArm build_pitman_arm(mb::MbSystem& s, const PitmanArmSpec& spec, int chassis, const Vec3& chassis_origin) {
  using mb::JointType;
  const Mat3 r = spec.orientation.toRotationMatrix();
  const auto at = [&](const Vec3& p) { return Vec3(chassis_origin + spec.location + r * p); };
  const auto axes_z = [&](const Vec3& d) {
    return Mat3(mb::Quat::FromTwoVectors(Vec3::UnitZ(), r * d).toRotationMatrix());
  };
  const auto add = [&](const std::string& name, const BodySpec& b) {
    mb::RigidBody body;
    body.name = spec.name + " " + name;
    body.mass = b.mass;
    body.inertia = b.inertia();
    body.position = at(b.com);
    return s.add_body(body);
  };
  PitmanArm p;
  p.link = add("link", spec.link);
  p.arm = add("arm", spec.arm);
  p.axis_chassis = r * spec.revolute_axis;
  p.revolute = s.add_joint("Pitman arm hinge", JointType::revolute, chassis, p.arm, at(spec.revolute_point),
                           axes_z(spec.revolute_axis));
  // The universal joint's frame: x along the arm's cross axis, y along the link's.
  Mat3 cross;
  cross.col(0) = r * spec.universal_axis_arm;
  cross.col(1) = r * spec.universal_axis_link;
  cross.col(2) = cross.col(0).cross(cross.col(1));
  s.add_joint("Pitman arm universal", JointType::universal, p.arm, p.link, at(spec.universal_point), cross);
  // The idler: a distance and a plane.
  s.joints.push_back(mb::Joint::place_pair("idler distance", JointType::distance, s.bodies, chassis,
                                           at(spec.idler_chassis), p.link, at(spec.idler_link)));
  s.joints.push_back(mb::Joint::place_pair("idler plane", JointType::point_on_plane, s.bodies, chassis,
                                           at(spec.idler_chassis), p.link, at(spec.idler_link),
                                           axes_z(spec.idler_axis)));
  return p;
}

double pitman_arm_angle(const mb::MbSystem& s, const PitmanArm& p) {
  // The joint allows turns about its axis only: the relative rotation's angle about that axis.
  const mb::RigidBody& arm = s.bodies[std::size_t(p.arm)];
  const mb::RigidBody& chassis = s.bodies[std::size_t(s.joints[std::size_t(p.revolute)].i)];
  const mb::Quat rel = chassis.orientation.conjugate() * arm.orientation;
  return 2 * std::atan2(rel.vec().dot(p.axis_chassis), rel.w());
}

void add_steering_servo(mb::MbSystem& s, const PitmanArmSpec& spec, const PitmanArm& p,
                        std::function<double(double)> input) {
  const int chassis = s.joints[std::size_t(p.revolute)].i;
  s.external.push_back({[=, &s](double t, const std::vector<mb::RigidBody>& b, std::vector<mb::Wrench>& w) {
                          const mb::RigidBody &arm = b[std::size_t(p.arm)], &ch = b[std::size_t(chassis)];
                          const Vec3 axis = ch.rotation() * p.axis_chassis;
                          const double rate = axis.dot(arm.rotation() * arm.omega - ch.rotation() * ch.omega);
                          // The arm turns clockwise seen from above (a negative angle about its upward axis) to steer
                          // left.
                          const double target = -spec.max_angle * std::clamp(input(t), -1.0, 1.0);
                          const double torque =
                              -spec.servo_stiffness * (pitman_arm_angle(s, p) - target) - spec.servo_damping * rate;
                          w[std::size_t(p.arm)].torque += arm.rotation().transpose() * (torque * axis);
                          w[std::size_t(chassis)].torque -= ch.rotation().transpose() * (torque * axis);
                        },
                        {p.arm, chassis}});
}

}  // namespace terracal::vehicle
