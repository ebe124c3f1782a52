#include "lowfi/scm_soil.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "core/json_file.hpp"
#include "lowfi/scm_nodes.hpp"

namespace terracal::lowfi {

const std::array<ScmSoilKey, 8>& scm_soil_keys() {
  static const std::array<ScmSoilKey, 8> keys = {{
      {"Bekker Kphi", &ScmSoil::Kphi, {0, 1e12, false, false, "Pa/m^n"}, true},
      {"Bekker Kc", &ScmSoil::Kc, {-1e12, 1e12, false, false, "Pa/m^(n-1)"}, true},
      {"Bekker n exponent", &ScmSoil::n, {0.05, 5}, true},
      {"Mohr cohesive limit", &ScmSoil::cohesion, {0, 1e8, false, false, "Pa"}, true},
      {"Mohr friction limit", &ScmSoil::friction_deg, {0, 89, false, false, "degrees"}, true},
      {"Janosi shear coefficient", &ScmSoil::janosi_k, {1e-6, 10, false, false, "m"}, true},
      {"Elastic stiffness", &ScmSoil::elastic_stiffness, {1, 1e13, false, false, "Pa/m"}, false},
      {"Damping", &ScmSoil::damping, {0, 1e10, false, false, "Pa s/m"}, false},
  }};
  return keys;
}

namespace {
void check_key(const ScmSoilKey& k, double v, const std::string& where) {
  if (!k.range.contains(v))
    throw InputError(
        fmt::format("{}: key 'Soil parameters.{}' = {}: expected in {}", where, k.name, v, k.range.text()));
}
}  // namespace

void validate(const ScmSoil& soil, const std::string& source) {
  for (const auto& k : scm_soil_keys()) check_key(k, soil.*k.field, source);
}

ScmSoil parse_scm_soil(const nlohmann::json& s, const std::string& where) {
  if (!s.is_object()) throw InputError(fmt::format("{}: 'Soil parameters' must be an object", where));
  ScmSoil soil;  // the defaults of the keys that may be left out
  for (const auto& k : scm_soil_keys()) {
    if (!s.contains(k.name)) {
      if (k.required) throw InputError(fmt::format("{}: key 'Soil parameters.{}' is missing", where, k.name));
      continue;
    }
    const nlohmann::json& v = s[k.name];
    if (!v.is_number())
      throw InputError(fmt::format("{}: key 'Soil parameters.{}': {} is not a number", where, k.name, v.dump()));
    soil.*k.field = v.get<double>();
    check_key(k, soil.*k.field, where);
  }
  for (const auto& [key, value] : s.items()) {
    const auto& keys = scm_soil_keys();
    if (std::none_of(keys.begin(), keys.end(), [&](const ScmSoilKey& k) { return key == k.name; }))
      throw InputError(fmt::format("{}: unknown key 'Soil parameters.{}'", where, key));
  }
  return soil;
}

ScmSoil read_scm_json(const std::string& path) {
  const nlohmann::json j = read_json_file(path, "SCM parameter file");
  if (!j.contains("Soil parameters"))
    throw InputError(fmt::format("{}: missing the object 'Soil parameters' (Chrono SCM JSON)", path));
  ScmSoil soil = parse_scm_soil(j["Soil parameters"], path);
  if (j.contains("Slip sinkage")) soil.slip_sinkage = parse_slip_sinkage(j["Slip sinkage"], path);
  return soil;
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
