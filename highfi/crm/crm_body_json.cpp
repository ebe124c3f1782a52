// Reading the bodies of a CRM scene (docs/crm_scene.md, `bodies[]`): shapes (with OBJ meshes),
// poses, motion programs and mass properties.
#include "highfi/crm/crm_body_json.hpp"

#include <charconv>
#include <cmath>
#include <sstream>
#include <type_traits>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "core/quat.hpp"
#include "core/text_check.hpp"

namespace terracal {

namespace {

// One number of an OBJ line; InputError naming the file, line and token otherwise.
template <class T>
T obj_number(const std::string& token, const std::filesystem::path& file, int line_no, const char* expected) {
  T v{};
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
  bool ok = ec == std::errc() && ptr == token.data() + token.size();
  if constexpr (std::is_floating_point_v<T>) ok = ok && std::isfinite(v);
  if (!ok) throw InputError(fmt::format("{}:{}: {} is not {}", file.string(), line_no, excerpt(token), expected));
  return v;
}

// Wavefront OBJ: `v x y z` and `f a b c` (polygons fanned into triangles; a/b/c and negative indices
// allowed); other statements (vt, vn, o, g, s, usemtl, ...) do not change the shape and are skipped.
void read_obj(const std::filesystem::path& file, BodyShape& shape, const std::string& key) {
  std::string bytes;
  try {
    bytes = read_input_bytes(file.string(), "mesh file");
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", key, e.what()));
  }
  std::istringstream in{std::string(check_utf8_text(file.string(), bytes))};
  std::string line;
  std::vector<int> face_line;  // the line of each triangle, to name it if it refers to no vertex
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    std::istringstream ls(line);
    std::string tag, tok;
    ls >> tag;
    if (tag == "v") {
      double x[3];
      for (double& c : x) {
        if (!(ls >> tok))
          throw InputError(
              fmt::format("{}:{}: a vertex needs 3 coordinates: {}", file.string(), line_no, excerpt(line)));
        c = obj_number<double>(tok, file, line_no, "a finite coordinate");
      }
      shape.vertices.push_back({x[0], x[1], x[2]});
    } else if (tag == "f") {
      std::vector<int> idx;
      while (ls >> tok) {
        const int k =
            obj_number<int>(tok.substr(0, tok.find('/')), file, line_no, "a vertex number (1, 2, ... or -1, -2, ...)");
        // Negative numbers count back from the last vertex defined above this line.
        if (k == 0 || int(shape.vertices.size()) + k < 0)
          throw InputError(
              fmt::format("{}:{}: {} is not a vertex number; expected 1 to N or -1 to -{} (the vertices "
                          "above this line)",
                          file.string(), line_no, k, shape.vertices.size()));
        idx.push_back(k > 0 ? k - 1 : int(shape.vertices.size()) + k);
      }
      if (idx.size() < 3) throw InputError(fmt::format("{}:{}: a face needs 3 vertices", file.string(), line_no));
      for (std::size_t q = 1; q + 1 < idx.size(); ++q) {
        shape.triangles.push_back({idx[0], idx[q], idx[q + 1]});
        face_line.push_back(line_no);
      }
    }
  }
  // After the whole file: a face may name a vertex defined below it.
  for (std::size_t t = 0; t < shape.triangles.size(); ++t)
    for (int v : shape.triangles[t])
      if (v < 0 || v >= int(shape.vertices.size()))
        throw InputError(fmt::format("{}:{}: a face refers to vertex {}; expected 1 to {}, the vertices of the file",
                                     file.string(), face_line[t], v + 1, shape.vertices.size()));
  if (shape.triangles.empty()) throw InputError(fmt::format("{}: mesh file '{}' has no faces", key, file.string()));
}

BodyShape parse_shape(JsonObject o, const std::filesystem::path& base) {
  BodyShape s;
  const std::string type = o.string_or("type", "", {"box", "cylinder", "disc", "annulus", "mesh"});
  if (type.empty()) o.fail("type", "is required: box, cylinder, disc, annulus or mesh");
  if (type == "box") {
    s.type = ShapeType::kBox;
    s.half_extents = 0.5 * o.vec3_or("size", {0, 0, 0});
    if (!(s.half_extents.x > 0 && s.half_extents.y > 0 && s.half_extents.z > 0))
      o.fail("size", "box size needs three positive lengths");
  } else if (type == "cylinder") {
    s.type = ShapeType::kCylinder;
    s.radius = o.number("radius", 0, 100, true);
    s.width = o.number("width", 0, 100, true);
    if (o.has("grousers")) {
      JsonObject g = o.object("grousers");
      s.grouser_count = int(g.integer_or("count", 0, 0, 1000));
      s.grouser_height = g.number_or("height", 0, 0, s.radius);
      s.grouser_thickness = g.number_or("thickness", 0, 0, s.radius);
      if (s.grouser_count > 0 && (s.grouser_height <= 0 || s.grouser_thickness <= 0))
        g.fail("height", "grousers need a positive height and thickness");
      g.finish();
    }
  } else if (type == "disc" || type == "annulus") {
    s.type = type == "disc" ? ShapeType::kDisc : ShapeType::kAnnulus;
    s.radius = o.number("radius", 0, 100, true);
    s.width = o.number("thickness", 0, 100, true);
    if (s.type == ShapeType::kAnnulus) s.inner_radius = o.number("inner_radius", 0, s.radius, true, true);
  } else {
    s.type = ShapeType::kMesh;
    const std::string file = o.string_or("file", "", {});
    if (file.empty()) o.fail("file", "a mesh shape needs an OBJ file");
    std::filesystem::path p(file);
    if (p.is_relative()) p = base / p;
    read_obj(p, s, o.key_path("file"));
  }
  o.finish();
  return s;
}

// A body's motion program: fixed, prescribed (constant velocities or a schedule) or dynamic (free
// degrees of freedom).
void parse_motion(JsonObject m, BodyMotion& motion) {
  const std::string mt = m.string_or("type", "prescribed", {"fixed", "prescribed", "dynamic"});
  motion.linear_velocity = m.vec3_or("linear_velocity", {});
  motion.angular_velocity = m.vec3_or("angular_velocity", {});
  const auto free = m.strings_or("free", {"x", "y", "z", "rx", "ry", "rz"});
  const char* names[6] = {"x", "y", "z", "rx", "ry", "rz"};
  for (const auto& f : free)
    for (int q = 0; q < 6; ++q) motion.free[q] = motion.free[q] || f == names[q];
  if (mt == "dynamic") motion.free.fill(true);
  if (m.has("schedule")) {
    if (mt != "prescribed") m.fail("schedule", "only a prescribed body follows a velocity schedule");
    if (m.has("linear_velocity") || m.has("angular_velocity"))
      m.fail("schedule", "give either constant velocities or a schedule, not both");
    const nlohmann::json& segs = m.raw("schedule");
    if (!segs.is_array() || segs.empty())
      m.fail("schedule", "must be a non-empty array of {duration, linear_velocity, angular_velocity}");
    for (std::size_t k = 0; k < segs.size(); ++k) {
      JsonObject g(segs[k], m.where(), m.key_path(fmt::format("schedule[{}]", k)));
      MotionSegment seg;
      seg.duration = g.number("duration", 0, 1e6, true);
      seg.linear_velocity = g.vec3_or("linear_velocity", {});
      seg.angular_velocity = g.vec3_or("angular_velocity", {});
      g.finish();
      motion.schedule.push_back(seg);
    }
    motion.linear_velocity = motion.schedule.front().linear_velocity;
    motion.angular_velocity = motion.schedule.front().angular_velocity;
  }
  if (mt == "fixed") {
    if (norm(motion.linear_velocity) > 0 || norm(motion.angular_velocity) > 0 || !free.empty())
      m.fail("type", "a fixed body takes no velocities and no free axes");
  }
  m.finish();
}

RigidBody parse_body(JsonObject o, const std::filesystem::path& base, int index) {
  RigidBody b;
  b.name = o.string_or("name", fmt::format("body{}", index), {});
  b.shape = parse_shape(o.object("shape"), base);
  b.position = o.vec3_or("position", {});
  if (o.has("rotation")) {
    JsonObject r = o.object("rotation");
    const Vec3<double> axis = r.vec3_or("axis", {0, 0, 1});
    if (norm(axis) == 0) r.fail("axis", "must not be zero");
    b.orientation = Quat::from_axis_angle(axis, r.number("angle_deg", -360, 360) * M_PI / 180.0);
    r.finish();
  }
  if (o.has("motion")) parse_motion(o.object("motion"), b.motion);
  b.inertia = o.vec3_or("inertia", {0, 0, 0});
  if (b.inertia.x < 0 || b.inertia.y < 0 || b.inertia.z < 0)
    o.fail("inertia", "principal moments must not be negative");
  if (b.motion.any_free()) {
    b.mass = o.number("mass", 0, 1e9, true);
    const Vec3<double>& I = b.inertia;
    bool rot_free = b.motion.free[3] || b.motion.free[4] || b.motion.free[5];
    if (rot_free && !(I.x > 0 && I.y > 0 && I.z > 0))
      o.fail("inertia", "a body free to rotate needs three positive principal moments");
  } else {
    b.mass = o.number_or("mass", 0, 0, 1e9);
  }
  b.applied_force = o.vec3_or("force", {});
  b.applied_torque = o.vec3_or("torque", {});
  b.load_ramp = o.number_or("load_ramp", 0, 0, 1e4);
  o.finish();
  return b;
}

}  // namespace

std::vector<RigidBody> parse_crm_bodies(JsonObject& scene, const std::filesystem::path& base) {
  std::vector<RigidBody> out;
  if (!scene.has("bodies")) return out;
  const nlohmann::json& bodies = scene.raw("bodies");
  if (!bodies.is_array()) scene.fail("bodies", "must be an array of body objects");
  for (std::size_t i = 0; i < bodies.size(); ++i)
    out.push_back(parse_body(JsonObject(bodies[i], scene.where(), fmt::format("bodies[{}]", i)), base, int(i)));
  return out;
}

}  // namespace terracal
