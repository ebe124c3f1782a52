#include "bayes/scm_json_read.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/errors.hpp"
#include "core/json_file.hpp"

namespace terracal::bayes {

ParamVector read_scm_soil_parameters(const std::string& path) {
  const nlohmann::json j = read_json_file(path, "SCM parameter file");
  if (!j.contains("Soil parameters") || !j["Soil parameters"].is_object())
    throw InputError(fmt::format("{}: missing the object 'Soil parameters' (Chrono SCM JSON)", path));
  const auto& s = j["Soil parameters"];
  ParamVector p{};
  for (int i = 0; i < kNumParams; ++i) {
    const std::string key(kChronoNames[i]);
    if (!s.contains(key)) throw InputError(fmt::format("{}: key 'Soil parameters.{}' is missing", path, key));
    if (!s[key].is_number())
      throw InputError(fmt::format("{}: key 'Soil parameters.{}': {} is not a number", path, key, s[key].dump()));
    p[i] = s[key].get<double>();
  }
  return p;
}

}  // namespace terracal::bayes
