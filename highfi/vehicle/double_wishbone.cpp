#include "highfi/vehicle/double_wishbone.hpp"

#include "highfi/vehicle/vehicle_json.hpp"

#include <fmt/format.h>

namespace terracal::vehicle {
namespace {
BodySpec read_body(JsonObject o, bool arm, ArmSpec* arm_out) {
  BodySpec b;
  b.mass = o.number("mass", 0, 1e5, true);
  b.com = read_point(o, "com");
  b.moments = read_moments(o, "inertia");
  if (o.has("products")) b.products = read_point(o, "products");
  if (arm) {
    arm_out->chassis_front = read_point(o, "chassis_front");
    arm_out->chassis_back = read_point(o, "chassis_back");
    arm_out->upright = read_point(o, "upright");
    if ((arm_out->chassis_front - arm_out->chassis_back).norm() < 1e-6)
      o.fail("chassis_back", "is at chassis_front; expected two points apart (the arm's hinge axis)");
  }
  o.finish();
  return b;
}

void read_spring(JsonObject o, DoubleWishboneSpec& s) {
  s.spring_chassis = read_point(o, "chassis");
  s.spring_arm = read_point(o, "arm");
  s.spring_free_length = o.number("free_length", 0, 10, true);
  if (o.has("stiffness")) {
    const double k = o.number("stiffness", 0, 1e9, true);
    s.spring_deflection = {-1, 1};
    s.spring_force = {-k, k};
  } else {
    const nlohmann::json& c = o.raw("curve");
    if (!c.is_array() || c.size() < 2) o.fail("curve", "expected [[deflection m, force N], ...] with 2 or more rows");
    for (std::size_t k = 0; k < c.size(); ++k) {
      if (!c[k].is_array() || c[k].size() != 2 || !c[k][0].is_number() || !c[k][1].is_number())
        o.fail("curve", fmt::format("row {} is {}; expected [deflection m, force N]", k, c[k].dump()));
      s.spring_deflection.push_back(c[k][0].get<double>());
      s.spring_force.push_back(c[k][1].get<double>());
      if (k > 0 && !(s.spring_deflection[k] > s.spring_deflection[k - 1]))
        o.fail("curve", fmt::format("row {}: deflection {} does not increase; expected increasing deflections", k,
                                    s.spring_deflection[k]));
    }
  }
  o.finish();
}
}  // namespace

Mat3 BodySpec::inertia() const {
  Mat3 j;
  j << moments.x(), products.x(), products.y(), products.x(), moments.y(), products.z(), products.y(), products.z(),
      moments.z();
  return j;
}

DoubleWishboneSpec read_double_wishbone(JsonObject o) {
  DoubleWishboneSpec s;
  o.string_or("template", "double_wishbone", {"double_wishbone"});
  s.name = read_name(o, s.name);
  if (o.has("source")) o.raw("source");  // where the numbers come from: for people, not read
  {
    JsonObject sp = o.object("spindle");
    s.spindle.mass = sp.number("mass", 0, 1e5, true);
    s.spindle.com = read_point(sp, "com");
    s.spindle.moments = read_moments(sp, "inertia");
    s.spindle_radius = sp.number_or("radius", s.spindle_radius, 0, 10, true);
    s.spindle_width = sp.number_or("width", s.spindle_width, 0, 10, true);
    sp.finish();
  }
  s.upright = read_body(o.object("upright"), false, nullptr);
  s.upper_arm.body = read_body(o.object("upper_arm"), true, &s.upper_arm);
  s.lower_arm.body = read_body(o.object("lower_arm"), true, &s.lower_arm);
  {
    JsonObject t = o.object("tierod");
    s.tierod_chassis = read_point(t, "chassis");
    s.tierod_upright = read_point(t, "upright");
    t.finish();
  }
  read_spring(o.object("spring"), s);
  {
    JsonObject sh = o.object("shock");
    s.shock_chassis = read_point(sh, "chassis");
    s.shock_arm = read_point(sh, "arm");
    s.shock_damping = sh.number("damping", 0, 1e8);
    sh.finish();
  }
  s.axle_inertia = o.number_or("axle_inertia", s.axle_inertia, 0, 1e3, true);
  o.finish();
  return s;
}

WishboneSide build_double_wishbone(mb::MbSystem& s, const DoubleWishboneSpec& spec, int chassis, int tierod_body,
                                   const Vec3& chassis_origin, const Vec3& location, double side) {
  using mb::JointType;
  const Vec3 mirror(1, side, 1);
  const auto at = [&](const Vec3& p) { return Vec3(chassis_origin + location + p.cwiseProduct(mirror)); };
  // Mirroring y flips the sign of the products that have one y index.
  const auto inertia = [&](const BodySpec& b) {
    BodySpec m = b;
    m.products = Vec3(b.products.x() * side, b.products.y(), b.products.z() * side);
    return m.inertia();
  };
  const std::string tag = side > 0 ? " L" : " R";
  const auto body = [&](const std::string& name, const BodySpec& b) {
    mb::RigidBody r;
    r.name = spec.name + " " + name + tag;
    r.mass = b.mass;
    r.inertia = inertia(b);
    r.position = at(b.com);
    return s.add_body(r);
  };
  WishboneSide w;
  w.side = side;
  w.spindle = body("spindle", spec.spindle);
  w.upright = body("upright", spec.upright);
  w.upper_arm = body("upper arm", spec.upper_arm.body);
  w.lower_arm = body("lower arm", spec.lower_arm.body);
  // Each arm hinges on the chassis about the line through its two chassis points.
  for (const auto& [arm, spec_arm, name] :
       {std::tuple{w.upper_arm, &spec.upper_arm, "upper"}, std::tuple{w.lower_arm, &spec.lower_arm, "lower"}}) {
    const Vec3 front = at(spec_arm->chassis_front), back = at(spec_arm->chassis_back);
    const Mat3 axes = mb::Quat::FromTwoVectors(Vec3::UnitZ(), (back - front).normalized()).toRotationMatrix();
    s.add_joint(std::string(name) + " arm hinge" + tag, JointType::revolute, chassis, arm, 0.5 * (front + back), axes);
    s.add_joint(std::string(name) + " ball joint" + tag, JointType::spherical, arm, w.upright, at(spec_arm->upright));
  }
  // The spindle turns about the lateral axis through its centre.
  const Mat3 lateral = mb::Quat::FromTwoVectors(Vec3::UnitZ(), Vec3::UnitY()).toRotationMatrix();
  w.spindle_joint =
      s.add_joint("spindle bearing" + tag, JointType::revolute, w.upright, w.spindle, at(spec.spindle.com), lateral);
  w.tierod_joint = s.add_joint("tie rod" + tag, JointType::distance, tierod_body, w.upright, at(spec.tierod_chassis),
                               Mat3::Identity(), at(spec.tierod_upright));
  const auto local = [&](int b, const Vec3& world) {
    return Vec3(s.bodies[std::size_t(b)].rotation().transpose() * (world - s.bodies[std::size_t(b)].position));
  };
  mb::SpringDamper spring;
  spring.name = "spring" + tag;
  spring.i = chassis;
  spring.j = w.lower_arm;
  spring.si = local(chassis, at(spec.spring_chassis));
  spring.sj = local(w.lower_arm, at(spec.spring_arm));
  spring.rest_length = spec.spring_free_length;
  spring.law = mb::table_law(spec.spring_deflection, spec.spring_force, {-1, 1}, {0, 0});
  s.springs.push_back(spring);
  mb::SpringDamper shock;
  shock.name = "shock" + tag;
  shock.i = chassis;
  shock.j = w.lower_arm;
  shock.si = local(chassis, at(spec.shock_chassis));
  shock.sj = local(w.lower_arm, at(spec.shock_arm));
  shock.rest_length = (at(spec.shock_arm) - at(spec.shock_chassis)).norm();
  shock.law = mb::linear_law(0, spec.shock_damping);
  s.springs.push_back(shock);
  return w;
}

}  // namespace terracal::vehicle
