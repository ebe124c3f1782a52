#pragma once
// The small readers the full vehicle's JSON objects share: points, principal moments of inertia and
// directions, each [x, y, z] checked where it is read (errors name the key path and the value).
#include <fmt/format.h>

#include "core/json_object.hpp"
#include "highfi/multibody/rigid_body.hpp"

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

}  // namespace terracal::vehicle
