// Reading and validating a CRM scene (docs/crm_scene.md). All checks happen here, before any
// particle exists; everything after works on the validated, immutable CrmScene.
#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/errors.hpp"
#include "core/json_file.hpp"
#include "core/json_object.hpp"
#include "highfi/crm_scene.hpp"
#include "highfi/lattice_stability.hpp"

namespace terracal {

CrmSoil parse_crm_soil(const nlohmann::json& j, const std::string& where) {
  JsonObject o(j, where, "soil");
  CrmSoil s;
  s.density = o.number("density", 0, 1e5, true);
  s.young_modulus = o.number("young_modulus", 0, 1e12, true);
  s.poisson_ratio = o.number("poisson_ratio", 0, 0.5, false, true);
  s.mu_s = o.number("mu_s", 0, 10);
  s.mu_2 = o.number_or("mu_2", s.mu_s, s.mu_s, 10);
  s.I0 = o.number_or("I0", 0.03, 0, 10, true);
  s.grain_diameter = o.number_or("grain_diameter", 0.005, 0, 1, true);
  s.cohesion = o.number_or("cohesion", 0, 0, 1e9);
  s.gravity = o.vec3_or("gravity", s.gravity);
  if (norm(s.gravity) > 1000) o.fail("gravity", fmt::format("|g| = {} m/s^2 is outside [0, 1000]", norm(s.gravity)));
  o.finish();
  return s;
}

namespace {

std::vector<std::string> effect_names() { return {kCrmEffectNames.begin(), kCrmEffectNames.end()}; }

// Wavefront OBJ: `v x y z` and `f a b c` (polygons fanned into triangles; a/b/c and negative indices allowed).
void read_obj(const std::filesystem::path& file, BodyShape& shape, const std::string& key) {
  std::ifstream in(file);
  if (!in) throw InputError(fmt::format("{}: cannot open the mesh file '{}'", key, file.string()));
  std::string line;
  int lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    std::istringstream ls(line);
    std::string tag;
    ls >> tag;
    if (tag == "v") {
      Vec3<double> v;
      if (!(ls >> v.x >> v.y >> v.z)) throw InputError(fmt::format("{}:{}: bad vertex line '{}'", file.string(), lineno, line));
      shape.vertices.push_back(v);
    } else if (tag == "f") {
      std::vector<int> idx;
      std::string tok;
      while (ls >> tok) {
        const int k = std::stoi(tok.substr(0, tok.find('/')));
        idx.push_back(k > 0 ? k - 1 : int(shape.vertices.size()) + k);
      }
      if (idx.size() < 3) throw InputError(fmt::format("{}:{}: a face needs 3 vertices", file.string(), lineno));
      for (std::size_t q = 1; q + 1 < idx.size(); ++q) shape.triangles.push_back({idx[0], idx[q], idx[q + 1]});
    }
  }
  for (const auto& t : shape.triangles)
    for (int v : t)
      if (v < 0 || v >= int(shape.vertices.size()))
        throw InputError(fmt::format("{}: a face refers to vertex {} of {}", file.string(), v + 1, shape.vertices.size()));
  if (shape.triangles.empty()) throw InputError(fmt::format("{}: mesh file '{}' has no faces", key, file.string()));
}

BodyShape parse_shape(JsonObject o, const std::filesystem::path& base) {
  BodyShape s;
  const std::string type = o.string_or("type", "", {"box", "cylinder", "disc", "annulus", "mesh"});
  if (type.empty()) o.fail("type", "is required: box, cylinder, disc, annulus or mesh");
  if (type == "box") {
    s.type = ShapeType::kBox;
    s.half_extents = 0.5 * o.vec3_or("size", {0, 0, 0});
    if (!(s.half_extents.x > 0 && s.half_extents.y > 0 && s.half_extents.z > 0)) o.fail("size", "box size needs three positive lengths");
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

CrmBody parse_body(JsonObject o, const std::filesystem::path& base, int index) {
  CrmBody b;
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
  const std::string type = o.has("motion") ? "" : "fixed";
  if (o.has("motion")) {
    JsonObject m = o.object("motion");
    const std::string mt = m.string_or("type", "prescribed", {"fixed", "prescribed", "dynamic"});
    b.motion.linear_velocity = m.vec3_or("linear_velocity", {});
    b.motion.angular_velocity = m.vec3_or("angular_velocity", {});
    const auto free = m.strings_or("free", {"x", "y", "z", "rx", "ry", "rz"});
    const char* names[6] = {"x", "y", "z", "rx", "ry", "rz"};
    for (const auto& f : free)
      for (int q = 0; q < 6; ++q) b.motion.free[q] = b.motion.free[q] || f == names[q];
    if (mt == "dynamic") b.motion.free.fill(true);
    if (m.has("schedule")) {
      if (mt != "prescribed") m.fail("schedule", "only a prescribed body follows a velocity schedule");
      if (m.has("linear_velocity") || m.has("angular_velocity"))
        m.fail("schedule", "give either constant velocities or a schedule, not both");
      const nlohmann::json& segs = m.raw("schedule");
      if (!segs.is_array() || segs.empty()) m.fail("schedule", "must be a non-empty array of {duration, linear_velocity, angular_velocity}");
      for (std::size_t k = 0; k < segs.size(); ++k) {
        JsonObject g(segs[k], m.where(), m.key_path(fmt::format("schedule[{}]", k)));
        MotionSegment seg;
        seg.duration = g.number("duration", 0, 1e6, true);
        seg.linear_velocity = g.vec3_or("linear_velocity", {});
        seg.angular_velocity = g.vec3_or("angular_velocity", {});
        g.finish();
        b.motion.schedule.push_back(seg);
      }
      b.motion.linear_velocity = b.motion.schedule.front().linear_velocity;
      b.motion.angular_velocity = b.motion.schedule.front().angular_velocity;
    }
    if (mt == "fixed") {
      if (norm(b.motion.linear_velocity) > 0 || norm(b.motion.angular_velocity) > 0 || !free.empty())
        m.fail("type", "a fixed body takes no velocities and no free axes");
    }
    m.finish();
  }
  if (b.motion.any_free()) {
    b.mass = o.number("mass", 0, 1e9, true);
    const Vec3<double> I = o.vec3_or("inertia", {0, 0, 0});
    bool rot_free = b.motion.free[3] || b.motion.free[4] || b.motion.free[5];
    if (rot_free && !(I.x > 0 && I.y > 0 && I.z > 0)) o.fail("inertia", "a body free to rotate needs three positive principal moments");
    b.inertia = I;
  } else {
    b.mass = o.number_or("mass", 0, 0, 1e9);
    b.inertia = o.vec3_or("inertia", {});
  }
  b.applied_force = o.vec3_or("force", {});
  b.applied_torque = o.vec3_or("torque", {});
  b.load_ramp = o.number_or("load_ramp", 0, 0, 1e4);
  o.finish();
  return b;
}

}  // namespace

void validate_crm_scene(CrmScene& sc) {
  const std::string& w = sc.source;
  auto fail = [&](const std::string& key, const std::string& what) {
    throw InputError(fmt::format("{}: key '{}': {}", w, key, what));
  };
  const CrmSoil& soil = sc.soil;
  if (!(soil.density > 0)) fail("soil.density", fmt::format("value {} must be > 0", soil.density));
  if (!(soil.young_modulus > 0)) fail("soil.young_modulus", fmt::format("value {} must be > 0", soil.young_modulus));
  if (!(soil.poisson_ratio >= 0 && soil.poisson_ratio < 0.5))
    fail("soil.poisson_ratio", fmt::format("value {} is outside [0, 0.5)", soil.poisson_ratio));
  if (soil.cohesion > 0 && !sc.effects.cohesion)
    fail("soil.cohesion", fmt::format("value {} Pa needs the effect \"cohesion\" in 'effects'", soil.cohesion));
  if (!(sc.settle_jitter >= 0 && sc.settle_jitter <= 0.3))
    fail("settle_jitter", fmt::format("value {} is outside [0, 0.3] (a fraction of the particle spacing)", sc.settle_jitter));
  if (sc.settle_seed < 0) fail("settle_seed", fmt::format("value {} is negative", sc.settle_seed));
  const CrmNumerics& n = sc.numerics;
  if (sc.effects.hourglass_damping && !(n.hourglass_alpha > 0 && n.hourglass_alpha <= 2))
    fail("hourglass_damping.alpha", fmt::format("value {} is outside (0, 2]", n.hourglass_alpha));
  if (sc.effects.hourglass_stiffness && !(n.hourglass_beta > 0 && n.hourglass_beta <= 0.1))
    fail("hourglass_stiffness.beta", fmt::format("value {} is outside (0, 0.1]", n.hourglass_beta));
  const double d0 = n.spacing;
  if (!(d0 > 0)) fail("resolution.spacing", fmt::format("value {} must be > 0", d0));
  if (!(n.h_over_d0 >= 1.0 && n.h_over_d0 <= 1.6))
    fail("resolution.h_over_d0", fmt::format("value {} is outside [1.0, 1.6] (default 1.4: the lattice is stable there)", n.h_over_d0));
  {
    // The lattice the bed starts from must be stable under its own weight, or a mode the velocity
    // gradient does not see grows from round-off and softens the bed (highfi/lattice_stability.hpp).
    const double szz = -soil.density * std::sqrt(dot(soil.gravity, soil.gravity)) * sc.bin.fill_height;
    const double k0 = soil.poisson_ratio / (1 - soil.poisson_ratio);
    const double lambda = soil.bulk_modulus() - 2 * soil.shear_modulus() / 3;
    const LatticeStability ls = lattice_stability(n.kernel, n.h_over_d0, d0, soil.density, lambda, soil.shear_modulus(),
                                                  {k0 * szz, k0 * szz, szz});
    if (ls.growth_rate > 1)
      spdlog::warn("{}: resolution.h_over_d0 {} with the {} kernel: the particle lattice is unstable under the bed's weight "
                   "(a mode at k d0/pi = ({:.2g}, {:.2g}, {:.2g}) grows at {:.3g} 1/s at its floor, unseen by the velocity "
                   "gradient; results/crm_settling). h/d0 = 1.4 with wendland_c2 keeps it stable.",
                   w, n.h_over_d0, n.kernel == KernelType::kWendlandC2 ? "wendland_c2" : "cubic_spline", ls.wave[0], ls.wave[1],
                   ls.wave[2], ls.growth_rate);
  }
  // The bin's walls sit on the particle lattice: its length and width are whole numbers of spacings.
  for (int q = 0; q < 2; ++q) sc.bin.size[q] = std::max(1.0, double(std::lround(sc.bin.size[q] / d0))) * d0;
  const CrmBin& bin = sc.bin;
  const double minimum_cells = 4;
  const char* axis[3] = {"x", "y", "z"};
  for (int q = 0; q < 2; ++q)
    if (bin.size[q] < minimum_cells * d0)
      fail("bin.size", fmt::format("{} = {} m is less than {} particle spacings ({} m): spacing too coarse for the bin",
                                   axis[q], bin.size[q], minimum_cells, minimum_cells * d0));
  if (bin.fill_height < 3 * d0)
    fail("bin.fill_height", fmt::format("value {} m is less than 3 spacings ({} m): spacing too coarse", bin.fill_height, 3 * d0));
  if (bin.fill_height > bin.size.z)
    fail("bin.fill_height", fmt::format("value {} m is above the wall height {} m", bin.fill_height, bin.size.z));
  if (bin.fill_length > bin.size.x + 1e-12)
    fail("bin.fill_length", fmt::format("value {} m is longer than the bin ({} m)", bin.fill_length, bin.size.x));
  if (bin.fill_length > 0 && bin.fill_length < 2 * d0)
    fail("bin.fill_length", fmt::format("value {} m is less than 2 spacings", bin.fill_length));
  // Speeds the CFL limit must cover: bodies, and free fall over the wall height.
  double speed = std::sqrt(2 * norm(soil.gravity) * bin.size.z);
  for (std::size_t b = 0; b < sc.bodies.size(); ++b) {
    const CrmBody& body = sc.bodies[b];
    const std::string key = fmt::format("bodies[{}] ({})", b, body.name);
    const BodyShape& s = body.shape;
    if (!(body.load_ramp >= 0)) fail(key + ".load_ramp", fmt::format("value {} s is negative", body.load_ramp));
    auto too_coarse = [&](const char* dim, double value, double need) {
      if (value < need * d0)
        fail(key + ".shape." + dim, fmt::format("value {} m is less than {} particle spacings ({} m): spacing too coarse for the body",
                                                value, need, need * d0));
    };
    switch (s.type) {
      case ShapeType::kBox: too_coarse("size", 2 * std::min({s.half_extents.x, s.half_extents.y, s.half_extents.z}), 1); break;
      case ShapeType::kCylinder: too_coarse("radius", s.radius, 3); too_coarse("width", s.width, 2); break;
      case ShapeType::kDisc: too_coarse("radius", s.radius, 2); too_coarse("thickness", s.width, 1); break;
      case ShapeType::kAnnulus: too_coarse("radius", s.radius, 2); too_coarse("thickness", s.width, 1);
        too_coarse("inner_radius (ring width)", s.radius - s.inner_radius, 1); break;
      case ShapeType::kMesh: too_coarse("file (mesh extent)", body.bounding_radius(), 2); break;
    }
    const Vec3<double>& p = body.position;
    if (p.x < 0 || p.x > bin.size.x || p.y < 0 || p.y > bin.size.y || p.z < 0)
      fail(key + ".position", fmt::format("[{}, {}, {}] is outside the bin [0, {}] x [0, {}] x [0, inf)", p.x, p.y, p.z,
                                          bin.size.x, bin.size.y));
    speed = std::max(speed, body.motion.max_speed(body.bounding_radius()));
  }
  sc.numerics.expected_speed = speed;
  const double limit = n.cfl_limit(soil, speed);
  if (n.time_step > 0) {
    if (n.time_step > limit * (1 + 1e-12))
      fail("resolution.time_step", fmt::format("value {} s is above the CFL limit 0.3 h / (c_s + v_max) = {:.4g} s "
                                               "(h = {} m, c_s = {:.4g} m/s, v_max = {:.3g} m/s)",
                                               n.time_step, limit, n.smoothing_length(), soil.sound_speed(), speed));
  } else {
    sc.numerics.time_step = n.cfl / 0.3 * limit;
  }
  if (!(sc.duration >= 0)) fail("duration", "must be >= 0");
}

CrmScene parse_crm_scene(const nlohmann::json& j, const std::string& where) {
  JsonObject o(j, where, "");
  CrmScene sc;
  sc.source = where;
  const std::filesystem::path base = std::filesystem::path(where).parent_path();
  if (o.has("soil") == o.has("soil_file")) o.fail("soil", "give exactly one of 'soil' (an object) or 'soil_file' (a path)");
  if (o.has("soil")) {
    sc.soil = parse_crm_soil(o.raw("soil"), where);
  } else {
    std::filesystem::path p(o.string_or("soil_file", "", {}));
    if (p.is_relative()) p = base / p;
    sc.soil = parse_crm_soil(read_json_file(p.string(), "soil file"), p.string());
  }
  {
    JsonObject b = o.object("bin");
    sc.bin.size = b.vec3_or("size", {0, 0, 0});
    if (!(sc.bin.size.x > 0 && sc.bin.size.y > 0 && sc.bin.size.z > 0)) b.fail("size", "needs three positive lengths [x, y, wall height]");
    sc.bin.fill_height = b.number("fill_height", 0, 1e3, true);
    sc.bin.fill_length = b.number_or("fill_length", 0, 0, 1e4, true);
    sc.bin.boundary_layers = int(b.integer_or("boundary_layers", 3, 3, 8));
    b.finish();
  }
  {
    JsonObject r = o.object("resolution");
    sc.numerics.spacing = r.number("spacing", 0, 10, true);
    sc.numerics.h_over_d0 = r.number_or("h_over_d0", CrmNumerics{}.h_over_d0, 0, 10, true);
    sc.numerics.kernel = r.string_or("kernel", "wendland_c2", {"wendland_c2", "cubic_spline"}) == "cubic_spline"
                             ? KernelType::kCubicSpline : KernelType::kWendlandC2;
    sc.numerics.cfl = r.number_or("cfl", 0.3, 0, 0.3, true);
    sc.numerics.time_step = r.number_or("time_step", 0, 0, 1, true);
    sc.numerics.cpu_precision = r.string_or("cpu_precision", "double", {"double", "float"}) == "float" ? CrmPrecision::kFloat
                                                                                                      : CrmPrecision::kDouble;
    sc.numerics.free_surface_support = r.number_or("free_surface_support", 0.8, 0, 1);
    sc.numerics.marker_velocity = marker_velocity_from_name(r.string_or("marker_velocity", "mirror", {"mirror", "mirror_image", "mirror_contact", "wall"}));
    sc.numerics.grid_reach = int(r.integer_or("grid_reach", 2, 1, 2));
    r.finish();
  }
  for (const auto& e : o.strings_or("effects", effect_names())) {
    if (e == "cohesion") sc.effects.cohesion = true;
    if (e == "artificial_viscosity") sc.effects.artificial_viscosity = true;
    if (e == "shifting") sc.effects.shifting = true;
    if (e == "active_domain") sc.effects.active_domain = true;
    if (e == "hourglass_damping") sc.effects.hourglass_damping = true;
    if (e == "hourglass_stiffness") sc.effects.hourglass_stiffness = true;
  }
  auto settings = [&](const char* name, bool on) {
    if (o.has(name) && !on) o.fail(name, fmt::format("settings given, but \"{}\" is not named in 'effects'", name));
  };
  settings("artificial_viscosity", sc.effects.artificial_viscosity);
  settings("shifting", sc.effects.shifting);
  settings("active_domain", sc.effects.active_domain);
  settings("hourglass_damping", sc.effects.hourglass_damping);
  settings("hourglass_stiffness", sc.effects.hourglass_stiffness);
  if (o.has("artificial_viscosity")) {
    JsonObject a = o.object("artificial_viscosity");
    sc.numerics.viscosity_alpha = a.number_or("alpha", 0.1, 0, 2);
    a.finish();
  }
  if (o.has("shifting")) {
    JsonObject a = o.object("shifting");
    sc.numerics.xsph = a.number_or("xsph", 0.5, 0, 1);
    a.finish();
  }
  if (o.has("hourglass_damping")) {
    JsonObject a = o.object("hourglass_damping");
    sc.numerics.hourglass_alpha = a.number_or("alpha", 0.4, 0, 2, true);
    a.finish();
  }
  if (o.has("hourglass_stiffness")) {
    JsonObject a = o.object("hourglass_stiffness");
    sc.numerics.hourglass_beta = a.number_or("beta", 0.03, 0, 0.1, true);
    a.finish();
  }
  if (o.has("active_domain")) {
    JsonObject a = o.object("active_domain");
    sc.numerics.active_margin = a.number_or("margin", 0.1, 0, 100, true);
    a.finish();
  }
  if (o.has("bodies")) {
    const nlohmann::json& bodies = o.raw("bodies");
    if (!bodies.is_array()) o.fail("bodies", "must be an array of body objects");
    for (std::size_t i = 0; i < bodies.size(); ++i)
      sc.bodies.push_back(parse_body(JsonObject(bodies[i], where, fmt::format("bodies[{}]", i)), base, int(i)));
  }
  sc.settle_time = o.number_or("settle_time", 0, 0, 1e4);
  sc.settle_jitter = o.number_or("settle_jitter", 0, 0, 0.3);
  sc.settle_seed = o.integer_or("settle_seed", kDefaultSettleSeed, 0, 1L << 62);
  sc.duration = o.number_or("duration", 0, 0, 1e6);
  if (o.has("output")) {
    JsonObject out = o.object("output");
    sc.output.vtu_every = out.integer_or("vtu_every", 0, 0, 1L << 40);
    sc.output.checkpoint_every = out.integer_or("checkpoint_every", 0, 0, 1L << 40);
    sc.output.progress_seconds = out.number_or("progress_seconds", 5, 0, 1e6, true);
    out.finish();
  }
  o.finish();
  validate_crm_scene(sc);
  return sc;
}

MarkerVelocity marker_velocity_from_name(const std::string& name) {
  if (name == "mirror") return MarkerVelocity::kMirror;
  if (name == "mirror_image") return MarkerVelocity::kMirrorImage;
  if (name == "mirror_contact") return MarkerVelocity::kMirrorContact;
  if (name == "wall") return MarkerVelocity::kWall;
  throw InputError(fmt::format("marker velocity {}: expected mirror, mirror_image, mirror_contact or wall", name));
}

const char* marker_velocity_name(MarkerVelocity v) {
  switch (v) {
    case MarkerVelocity::kMirrorImage: return "mirror_image";
    case MarkerVelocity::kMirrorContact: return "mirror_contact";
    case MarkerVelocity::kWall: return "wall";
    case MarkerVelocity::kMirror: break;
  }
  return "mirror";
}

CrmScene load_crm_scene(const std::filesystem::path& file) {
  return parse_crm_scene(read_json_file(file.string(), "scene file"), file.string());
}

}  // namespace terracal
