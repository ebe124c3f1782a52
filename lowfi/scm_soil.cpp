#include "lowfi/scm_soil.hpp"

#include <fmt/format.h>

#include "core/errors.hpp"
#include "core/json_file.hpp"
#include "lowfi/scm_nodes.hpp"

namespace terracal::lowfi {

namespace {

// One key of the block: present (unless it has a default), a number, within [lo, hi].
double read_key(const nlohmann::json& s, const std::string& where, const char* key, double lo, double hi,
                const char* range, const double* fallback = nullptr) {
  if (!s.contains(key)) {
    if (fallback) return *fallback;
    throw InputError(fmt::format("{}: key 'Soil parameters.{}' is missing", where, key));
  }
  if (!s[key].is_number())
    throw InputError(fmt::format("{}: key 'Soil parameters.{}': {} is not a number", where, key, s[key].dump()));
  const double v = s[key].get<double>();
  if (!(v >= lo && v <= hi))
    throw InputError(fmt::format("{}: key 'Soil parameters.{}' = {}: expected {}", where, key, v, range));
  return v;
}

}  // namespace

ScmSoil parse_scm_soil(const nlohmann::json& s, const std::string& where) {
  if (!s.is_object()) throw InputError(fmt::format("{}: 'Soil parameters' must be an object", where));
  ScmSoil soil;
  const double ke = soil.elastic_stiffness, damping = soil.damping;
  soil.Kphi = read_key(s, where, "Bekker Kphi", 0, 1e12, "in [0, 1e12] Pa/m^n");
  soil.Kc = read_key(s, where, "Bekker Kc", -1e12, 1e12, "in [-1e12, 1e12] Pa/m^(n-1)");
  soil.n = read_key(s, where, "Bekker n exponent", 0.05, 5, "in [0.05, 5]");
  soil.cohesion = read_key(s, where, "Mohr cohesive limit", 0, 1e8, "in [0, 1e8] Pa");
  soil.friction_deg = read_key(s, where, "Mohr friction limit", 0, 89, "in [0, 89] degrees");
  soil.janosi_k = read_key(s, where, "Janosi shear coefficient", 1e-6, 10, "in [1e-6, 10] m");
  soil.elastic_stiffness = read_key(s, where, "Elastic stiffness", 1, 1e13, "in [1, 1e13] Pa/m", &ke);
  soil.damping = read_key(s, where, "Damping", 0, 1e10, "in [0, 1e10] Pa s/m", &damping);
  for (const auto& [key, value] : s.items()) {
    static const char* known[] = {"Bekker Kphi",         "Bekker Kc",
                                  "Bekker n exponent",   "Mohr cohesive limit",
                                  "Mohr friction limit", "Janosi shear coefficient",
                                  "Elastic stiffness",   "Damping"};
    bool ok = false;
    for (const char* k : known) ok = ok || key == k;
    if (!ok) throw InputError(fmt::format("{}: unknown key 'Soil parameters.{}'", where, key));
  }
  return soil;
}

ScmSoil read_scm_json(const std::string& path) {
  const nlohmann::json j = read_json_file(path, "SCM parameter file");
  if (!j.contains("Soil parameters"))
    throw InputError(fmt::format("{}: missing the object 'Soil parameters' (Chrono SCM JSON)", path));
  return parse_scm_soil(j["Soil parameters"], path);
}

double scm_memory_bytes(double grid, double footprint_area, double swept_area) {
  // A hash-map node: the ScmNode, its key, the next pointer and the allocator's header, and a bucket
  // pointer (load factor 1); and the contact list's pointer.
  const double per_node = sizeof(ScmNode) + sizeof(std::int64_t) + 3 * sizeof(void*) + sizeof(void*);
  // Per ray: the underside's height, the coarse and wanted flags, and a candidate hit and a pressed
  // hit with their node pointer and index (ScmTerrain::Scratch) at most.
  const double per_ray = sizeof(double) + 2 + 2 * 48 + sizeof(void*) + 2 * sizeof(int);
  const double cell = grid * grid;
  return swept_area / cell * per_node + footprint_area / cell * per_ray;
}

nlohmann::json scm_soil_json(const ScmSoil& s) {
  return {{"Bekker Kphi", s.Kphi},
          {"Bekker Kc", s.Kc},
          {"Bekker n exponent", s.n},
          {"Mohr cohesive limit", s.cohesion},
          {"Mohr friction limit", s.friction_deg},
          {"Janosi shear coefficient", s.janosi_k},
          {"Elastic stiffness", s.elastic_stiffness},
          {"Damping", s.damping}};
}

}  // namespace terracal::lowfi
