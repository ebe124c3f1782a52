#include "highfi/vehicle/rack_pinion.hpp"

#include <algorithm>
#include <cmath>

#include "highfi/vehicle/vehicle_json.hpp"

namespace terracal::vehicle {

RackPinionSpec read_rack_pinion(JsonObject o) {
  RackPinionSpec s;
  o.string_or("template", "rack_pinion", {"rack_pinion"});
  s.name = read_name(o, s.name);
  if (o.has("source")) o.raw("source");
  s.rack = read_part(o.object("rack"));
  if (o.has("axis")) s.axis = read_direction(o, "axis");
  {
    JsonObject p = o.object("pinion");
    s.pinion_radius = p.number("radius", 0, 1, true);
    s.max_angle = p.number("max_angle", 0, 4 * M_PI, true);
    p.finish();
  }
  s.location = read_point(o, "location");
  s.orientation = read_orientation(o);
  read_servo(o, s.servo_stiffness, s.servo_damping);
  o.finish();
  return s;
}

RackPinion build_rack_pinion(mb::MbSystem& s, const RackPinionSpec& spec, int chassis, const Vec3& chassis_origin) {
  const Mat3 r = spec.orientation.toRotationMatrix();
  RackPinion out;
  out.axis_chassis = r * spec.axis;
  out.built_at = spec.location + r * spec.rack.com;
  mb::RigidBody rack;
  rack.name = spec.name + " rack";
  rack.mass = spec.rack.mass;
  rack.inertia = spec.rack.inertia();
  rack.position = chassis_origin + out.built_at;
  out.rack = s.add_body(rack);
  out.prismatic = s.add_joint(spec.name + " slide", mb::JointType::prismatic, chassis, out.rack, rack.position,
                              Mat3(mb::Quat::FromTwoVectors(Vec3::UnitZ(), out.axis_chassis).toRotationMatrix()));
  return out;
}

double rack_travel(const mb::MbSystem& s, const RackPinion& r) {
  const mb::RigidBody& chassis = s.bodies[std::size_t(s.joints[std::size_t(r.prismatic)].i)];
  const mb::RigidBody& rack = s.bodies[std::size_t(r.rack)];
  // The chassis frame's origin lies at chassis.position - R com; the rack's built centre is r.built_at
  // from it, so the travel is measured against the chassis point that coincided with it.
  const mb::Joint& j = s.joints[std::size_t(r.prismatic)];
  return (rack.point(j.sj) - chassis.point(j.si)).dot(chassis.rotation() * r.axis_chassis);
}

void add_rack_servo(mb::MbSystem& s, const RackPinionSpec& spec, const RackPinion& r,
                    std::function<double(double)> input) {
  const int chassis = s.joints[std::size_t(r.prismatic)].i;
  s.external.push_back(
      {[=, &s](double t, const std::vector<mb::RigidBody>& b, std::vector<mb::Wrench>& w) {
         const mb::RigidBody &rack = b[std::size_t(r.rack)], &ch = b[std::size_t(chassis)];
         const Vec3 axis = ch.rotation() * r.axis_chassis;
         const double rate =
             axis.dot(rack.velocity - ch.point_velocity(ch.rotation().transpose() * (rack.position - ch.position)));
         const double target = spec.max_travel() * std::clamp(input(t), -1.0, 1.0);
         const double force = -spec.servo_stiffness * (rack_travel(s, r) - target) - spec.servo_damping * rate;
         mb::add_force_at(rack, Vec3::Zero(), force * axis, w[std::size_t(r.rack)]);
         mb::add_force_at(ch, ch.rotation().transpose() * (rack.position - ch.position), -force * axis,
                          w[std::size_t(chassis)]);
       },
       {r.rack, chassis}});
}

}  // namespace terracal::vehicle
