// Reading a CRM scene (docs/crm_scene.md): every key is taken once, typed and range-checked, then
// validate_crm_scene (crm_scene_check.cpp) applies the scene's rules; everything after works on the
// validated, immutable CrmScene.
#include <cmath>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/errors.hpp"
#include "core/json_file.hpp"
#include "core/json_object.hpp"
#include "highfi/crm/crm_body_json.hpp"
#include "highfi/crm/crm_scene.hpp"

namespace terracal {

CrmSoil parse_crm_soil(const nlohmann::json& j, const std::string& where) {
  JsonObject o(j, where, "soil");
  CrmSoil s;
  s.density = o.number("density", 0, 1e5, true);
  s.young_modulus = o.number("young_modulus", 0, 1e12, true);
  s.poisson_ratio = o.number("poisson_ratio", 0, 0.5, false, true);
  s.mu_s = o.number("mu_s", 0, 10);
  s.mu_2 = o.number_or("mu_2", s.mu_s, s.mu_s, 10);
  s.I0 = o.number_or("I0", s.I0, 0, 10, true);
  s.grain_diameter = o.number_or("grain_diameter", s.grain_diameter, 0, 1, true);
  s.cohesion = o.number_or("cohesion", s.cohesion, 0, 1e9);
  s.gravity = o.vec3_or("gravity", s.gravity);
  if (norm(s.gravity) > 1000) o.fail("gravity", fmt::format("|g| = {} m/s^2 is outside [0, 1000]", norm(s.gravity)));
  // The bed lies on the bin's floor: gravity points down. Without any (the tests' stress-free beds)
  // nothing settles and nothing has weight: allowed, with a warning.
  if (norm(s.gravity) > 0 && !(s.gravity.z < 0))
    o.fail("gravity", fmt::format("[{}, {}, {}] m/s^2 does not point down; expected g_z < 0, such as [0, 0, -9.81]",
                                  s.gravity.x, s.gravity.y, s.gravity.z));
  if (norm(s.gravity) == 0)
    spdlog::warn("{}: key '{}': [0, 0, 0]: the soil has no weight, so it neither settles nor carries a load", where,
                 o.key_path("gravity"));
  o.finish();
  return s;
}

namespace {

CrmSoil read_soil(JsonObject& o, const std::filesystem::path& base) {
  if (o.has("soil") == o.has("soil_file"))
    o.fail("soil", "give exactly one of 'soil' (an object) or 'soil_file' (a path)");
  if (o.has("soil")) return parse_crm_soil(o.raw("soil"), o.where());
  std::filesystem::path p(o.string_or("soil_file", "", {}));
  if (p.is_relative()) p = base / p;
  return parse_crm_soil(read_json_file(p.string(), "soil file"), p.string());
}

CrmBin read_bin(JsonObject b) {
  CrmBin bin;
  bin.size = b.vec3_or("size", {0, 0, 0});
  if (!(bin.size.x > 0 && bin.size.y > 0 && bin.size.z > 0))
    b.fail("size", "needs three positive lengths [x, y, wall height]");
  bin.fill_height = b.number("fill_height", 0, 1e3, true);
  bin.fill_length = b.number_or("fill_length", 0, 0, 1e4, true);
  bin.boundary_layers = int(b.integer_or("boundary_layers", 3, 3, 8));
  b.finish();
  return bin;
}

CrmNumerics read_resolution(JsonObject r) {
  CrmNumerics n;
  n.spacing = r.number("spacing", CrmRanges::kSpacing);
  n.h_over_d0 = r.number_or("h_over_d0", n.h_over_d0, CrmRanges::kHOverD0);
  n.kernel = r.string_or("kernel", "wendland_c2", {"wendland_c2", "cubic_spline"}) == "cubic_spline"
                 ? KernelType::kCubicSpline
                 : KernelType::kWendlandC2;
  n.cfl = r.number_or("cfl", n.cfl, 0, 0.3, true);
  n.time_step = r.number_or("time_step", 0, CrmRanges::kTimeStep);
  n.cpu_precision = r.string_or("cpu_precision", "double", {"double", "float"}) == "float" ? CrmPrecision::kFloat
                                                                                           : CrmPrecision::kDouble;
  n.free_surface_support = r.number_or("free_surface_support", n.free_surface_support, 0, 1);
  n.marker_velocity = marker_velocity_from_name(
      r.string_or("marker_velocity", "mirror", {std::begin(kMarkerVelocityNames), std::end(kMarkerVelocityNames)}));
  n.wall_contact = r.number_or("wall_contact", n.wall_contact, 0, 100);
  n.grid_reach = int(r.integer_or("grid_reach", n.grid_reach, 1, 2));
  n.sort_skin = r.number_or("sort_skin", n.sort_skin, 0, 0.5);
  r.finish();
  return n;
}

void read_settling(JsonObject& o, CrmScene& sc) {
  sc.settle_time = o.number_or("settle_time", 0, CrmRanges::kSettleTime);
  sc.settle_jitter = o.number_or("settle_jitter", 0, CrmRanges::kSettleJitter);
  sc.settle_seed = o.integer_or("settle_seed", kDefaultSettleSeed, 0, CrmRanges::kMaxSettleSeed);
}

CrmOutputSettings read_output(JsonObject out) {
  CrmOutputSettings s;
  s.vtu_every = out.integer_or("vtu_every", 0, 0, 1L << 40);
  s.vtu_from = out.number_or("vtu_from", 0, 0, 1e6);
  s.checkpoint_every = out.integer_or("checkpoint_every", 0, 0, 1L << 40);
  s.progress_seconds = out.number_or("progress_seconds", s.progress_seconds, 0, 1e6, true);
  out.finish();
  return s;
}

CrmRunLimits read_checks(JsonObject o) {
  CrmRunLimits c;
  c.max_lost_fraction = o.number_or("max_lost_fraction", c.max_lost_fraction, 0, 1);
  o.finish();
  return c;
}

}  // namespace

CrmScene parse_crm_scene(const nlohmann::json& j, const std::string& where) {
  JsonObject o(j, where, "");
  CrmScene sc;
  sc.source = where;
  const std::filesystem::path base = std::filesystem::path(where).parent_path();
  sc.soil = read_soil(o, base);
  sc.bin = read_bin(o.object("bin"));
  sc.numerics = read_resolution(o.object("resolution"));
  sc.effects = read_effects<CrmEffects>(o);
  sc.bodies = parse_crm_bodies(o, base);
  read_settling(o, sc);
  sc.duration = o.number_or("duration", 0, 0, 1e6);
  if (o.has("output")) sc.output = read_output(o.object("output"));
  if (o.has("checks")) sc.checks = read_checks(o.object("checks"));
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
    case MarkerVelocity::kMirrorImage:
      return "mirror_image";
    case MarkerVelocity::kMirrorContact:
      return "mirror_contact";
    case MarkerVelocity::kWall:
      return "wall";
    case MarkerVelocity::kMirror:
      break;
  }
  return "mirror";
}

CrmScene load_crm_scene(const std::filesystem::path& file) {
  return parse_crm_scene(read_json_file(file.string(), "scene file"), file.string());
}

}  // namespace terracal
