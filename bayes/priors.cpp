#include "bayes/priors.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "core/errors.hpp"
#include "core/json_file.hpp"
#include "core/text_check.hpp"

namespace terracal::bayes {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Hard physical limits: a priors file may narrow them, never widen them.
constexpr std::array<Range, kNumParams> kPhysical = {{
    {-1e9, 1e9},               // Kc
    {0.0, 1e11},               // Kphi
    {0.0, 2.0, true, false},   // n: 0 < n <= 2
    {0.0, 1e7},                // c
    {0.0, 60.0},               // phi [deg]
    {0.0, 10.0, true, false},  // k > 0
    {0.0, 20.0},               // S, as the block "Slip sinkage" allows
    {0.0, 100.0, true, false}, // R > 0
    {0.0, 10.0, true, false},  // k_annulus > 0
}};

double get_number(const nlohmann::json& j, const std::string& path, const std::string& key, const char* field) {
  if (!j.contains(field)) throw InputError(fmt::format("{}: key '{}': missing field '{}'", path, key, field));
  if (!j[field].is_number())
    throw InputError(fmt::format("{}: key '{}.{}': {} is not a number", path, key, field, shorten(j[field].dump())));
  return j[field].get<double>();
}

// The fields each type of prior reads. Any other field is refused: a misspelt "uper" would
// otherwise leave the default bound in place without a word.
std::vector<std::string> fields_of(const std::string& type) {
  if (type == "uniform") return {"type", "lower", "upper"};
  if (type == "normal" || type == "lognormal") return {"type", "mean", "sd", "lower", "upper"};
  if (type == "fixed") return {"type", "value"};
  return {};  // not a type: refused by the caller, which names the types
}

void refuse_unknown_fields(const nlohmann::json& spec, const std::string& path, const std::string& key,
                           const std::string& type) {
  const std::vector<std::string> fields = fields_of(type);
  if (fields.empty()) return;
  for (const auto& [field, value] : spec.items())
    if (std::find(fields.begin(), fields.end(), field) == fields.end())
      throw InputError(fmt::format("{}: key {}: unknown key for a {} prior; expected {}", path,
                                   excerpt(key + "." + field), type, fmt::join(fields, ", ")));
}

}  // namespace

double Prior::log_density(double x) const {
  if (kind == Kind::kFixed) return x == value ? 0.0 : -kInf;
  if (!contains(x)) return -kInf;
  switch (kind) {
    case Kind::kNormal:
      return -0.5 * std::pow((x - mean) / sd, 2);
    case Kind::kLogNormal:
      return x > 0 ? -0.5 * std::pow((std::log(x) - mean) / sd, 2) - std::log(x) : -kInf;
    default:
      return 0.0;
  }
}

std::string Prior::describe() const {
  switch (kind) {
    case Kind::kFixed:
      return fmt::format("fixed at {}", value);
    case Kind::kNormal:
      return fmt::format("normal(mean {}, sd {}) on [{}, {}]", mean, sd, lower, upper);
    case Kind::kLogNormal:
      return fmt::format("lognormal(log-mean {}, log-sd {}) on [{}, {}]", mean, sd, lower, upper);
    default:
      return fmt::format("uniform on [{}, {}]", lower, upper);
  }
}

Priors default_priors() {
  Priors p;
  const std::array<std::pair<double, double>, kNumParams> bounds = {{
      {-1e7, 1e7},  // Kc [Pa/m^(n-1)]
      {0.0, 1e9},   // Kphi [Pa/m^n]
      {1e-3, 2.0},  // n
      {0.0, 2e5},   // c [Pa]
      {0.0, 60.0},  // phi [deg]
      {1e-5, 1.0},  // k [m]
      {0.0, 10.0},  // S: Lyasko's 1.5; CRM's wheels sink as with S near 3
      {0.1, 10.0},  // R: the set's shear strength over the annulus's
      {1e-5, 1.0},  // k_annulus [m]
  }};
  for (int i = 0; i < kNumParams; ++i) {
    p[i].lower = bounds[i].first;
    p[i].upper = bounds[i].second;
  }
  return p;
}

Prior fixed_prior(double value) {
  Prior p;
  p.kind = Prior::Kind::kFixed;
  p.value = p.lower = p.upper = value;
  p.user_given = true;
  return p;
}

Prior parse_prior(const nlohmann::json& spec, const std::string& path, const std::string& key, const Range& allowed,
                  const Prior& base) {
  if (!spec.is_object() || !spec.contains("type") || !spec["type"].is_string())
    throw InputError(fmt::format("{}: key '{}': expected an object with a string field 'type'", path, key));
  Prior pr = base;
  pr.user_given = true;
  const std::string type = spec["type"];
  refuse_unknown_fields(spec, path, key, type);
  if (spec.contains("lower")) pr.lower = get_number(spec, path, key, "lower");
  if (spec.contains("upper")) pr.upper = get_number(spec, path, key, "upper");
  if (type == "uniform") {
    pr.kind = Prior::Kind::kUniform;
  } else if (type == "normal" || type == "lognormal") {
    pr.kind = type == "normal" ? Prior::Kind::kNormal : Prior::Kind::kLogNormal;
    pr.mean = get_number(spec, path, key, "mean");
    pr.sd = get_number(spec, path, key, "sd");
    if (!(pr.sd > 0)) throw InputError(fmt::format("{}: key '{}.sd': {} must be > 0", path, key, pr.sd));
  } else if (type == "fixed") {
    const double value = get_number(spec, path, key, "value");
    if (!allowed.contains(value))
      throw InputError(
          fmt::format("{}: key '{}.value': {} is outside the physical range {}", path, key, value, allowed.text()));
    return fixed_prior(value);
  } else {
    throw InputError(
        fmt::format("{}: key '{}.type': {} is not a prior type; expected uniform, normal, lognormal or fixed", path,
                    key, excerpt(type)));
  }
  if (!(pr.lower < pr.upper))
    throw InputError(fmt::format("{}: key '{}': lower {} must be below upper {}", path, key, pr.lower, pr.upper));
  if (!allowed.contains(pr.lower))
    throw InputError(
        fmt::format("{}: key '{}.lower': {} is outside the physical range {}", path, key, pr.lower, allowed.text()));
  if (!allowed.contains(pr.upper))
    throw InputError(
        fmt::format("{}: key '{}.upper': {} is outside the physical range {}", path, key, pr.upper, allowed.text()));
  return pr;
}

Priors load_priors(const std::string& path) {
  const nlohmann::json j = read_json_file(path, "priors file");
  if (!j.is_object()) throw InputError(fmt::format("{}: expected a JSON object keyed by parameter name", path));
  Priors p = default_priors();
  std::array<std::string, kNumParams> named_by;  // a short and a Chrono name for one parameter: refused
  for (const auto& [key, spec] : j.items()) {
    const int i = param_index(key);
    if (i < 0)
      throw InputError(fmt::format("{}: unknown key {}; expected one of Kc, Kphi, n, c, phi, k, S, R, k_annulus (or their Chrono names)",
                                   path, excerpt(key)));
    if (!named_by[i].empty())
      throw InputError(fmt::format("{}: keys '{}' and '{}' both give the prior of {}; expected one of them", path,
                                   named_by[i], key, kShortNames[i]));
    named_by[i] = key;
    p[i] = parse_prior(spec, path, key, kPhysical[i], p[i]);
  }
  return p;
}

}  // namespace terracal::bayes
