#pragma once
// The small readers the full vehicle's JSON objects share: points, principal moments of inertia and
// directions, each [x, y, z] checked where it is read (errors name the key path and the value).
#include <cmath>

#include <fmt/format.h>

#include "core/json_object.hpp"
#include "highfi/multibody/rigid_body.hpp"
#include "highfi/vehicle/double_wishbone.hpp"

namespace terracal::vehicle {

// [x, y, z], three finite numbers.
inline mb::Vec3 read_point(JsonObject& o, const std::string& key) {
  const nlohmann::json& j = o.raw(key);
  if (!j.is_array() || j.size() != 3 || !j[0].is_number() || !j[1].is_number() || !j[2].is_number())
    o.fail(key, fmt::format("value {} is not a point or vector; expected [x, y, z]", j.dump()));
  const mb::Vec3 v(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
  if (!v.allFinite()) o.fail(key, fmt::format("value {} is not finite", j.dump()));
  return v;
}

// Principal moments of inertia, each > 0 (kg m^2).
inline mb::Vec3 read_moments(JsonObject& o, const std::string& key) {
  const mb::Vec3 v = read_point(o, key);
  if (!(v.minCoeff() > 0))
    o.fail(key, fmt::format("value [{}, {}, {}] has a moment <= 0; expected > 0 (kg m^2)", v.x(), v.y(), v.z()));
  return v;
}

// A direction (normalised; not zero).
inline mb::Vec3 read_direction(JsonObject& o, const std::string& key) {
  const mb::Vec3 d = read_point(o, key);
  if (d.norm() < 1e-9) o.fail(key, "is a zero vector; expected a direction");
  return d.normalized();
}

// An optional "name" string.
inline std::string read_name(JsonObject& o, const std::string& fallback) {
  if (!o.has("name")) return fallback;
  const nlohmann::json& n = o.raw("name");
  if (!n.is_string()) o.fail("name", fmt::format("value {} is not a string", n.dump()));
  return n.get<std::string>();
}

// A rigid part: "mass", "com" [x, y, z], principal "inertia" [Ixx, Iyy, Izz].
inline BodySpec read_part(JsonObject o) {
  BodySpec b;
  b.mass = o.number("mass", 0, 1e5, true);
  b.com = read_point(o, "com");
  b.moments = read_moments(o, "inertia");
  o.finish();
  return b;
}

// An optional "orientation" [w, x, y, z], a unit quaternion (to 1e-3; normalised).
inline mb::Quat read_orientation(JsonObject& o) {
  if (!o.has("orientation")) return mb::Quat::Identity();
  const nlohmann::json& q = o.raw("orientation");
  if (!q.is_array() || q.size() != 4 || !q[0].is_number() || !q[1].is_number() || !q[2].is_number() ||
      !q[3].is_number())
    o.fail("orientation", fmt::format("value {} is not a quaternion; expected [w, x, y, z]", q.dump()));
  mb::Quat r(q[0].get<double>(), q[1].get<double>(), q[2].get<double>(), q[3].get<double>());
  if (std::abs(r.norm() - 1) > 1e-3)
    o.fail("orientation", fmt::format("has norm {}; expected a unit quaternion", r.norm()));
  return r.normalized();
}

// An optional "servo" object: "stiffness" (> 0) and "damping" (>= 0), kept as given where absent.
inline void read_servo(JsonObject& o, double& stiffness, double& damping) {
  if (!o.has("servo")) return;
  JsonObject v = o.object("servo");
  stiffness = v.number_or("stiffness", stiffness, 0, 1e12, true);
  damping = v.number_or("damping", damping, 0, 1e12);
  v.finish();
}

}  // namespace terracal::vehicle
