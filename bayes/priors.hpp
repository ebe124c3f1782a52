#pragma once
// Priors on the six SCM parameters. Default: bounded uniform within physical limits. A JSON
// priors file overrides bounds, chooses normal or lognormal priors (truncated to the bounds), or
// fixes a parameter. Validated once into this immutable form.
#include <array>
#include <string>

#include <nlohmann/json.hpp>

#include "bayes/scm_parameters.hpp"
#include "core/range.hpp"

namespace terracal::bayes {

struct Prior {
  enum class Kind { kUniform, kNormal, kLogNormal, kFixed };
  Kind kind = Kind::kUniform;
  double lower = 0, upper = 0;  // support (normal and lognormal are truncated to it)
  double mean = 0, sd = 0;      // normal: of the value; lognormal: of its natural log
  double value = 0;             // fixed
  bool user_given = false;      // from a priors file (not the default)

  bool fixed() const { return kind == Kind::kFixed; }
  bool contains(double x) const { return x >= lower && x <= upper; }
  double log_density(double x) const;  // up to a constant; -inf outside the support
  std::string describe() const;
};

using Priors = std::array<Prior, kNumParams>;

// Physical limits: 0 < n <= 2, 0 <= phi <= 60 deg, c >= 0, k > 0; Kc may be
// negative (Kc/r + Kphi > 0 is enforced per plate radius by the problem).
Priors default_priors();

// A parameter fixed at `value` by the user (a priors file's {"type": "fixed"}, or a command that
// fixes one, as `pipeline` fixes Kc = 0 when the free-Kc set cannot drive the SCM wheel).
Prior fixed_prior(double value);

// Reads a priors file: {"Kphi": {"type": "uniform", "lower": 1e5, "upper": 1e8},
// "n": {"type": "normal", "mean": 1.0, "sd": 0.2}, "k": {"type": "lognormal", "mean": -4.6, "sd": 0.5},
// "Kc": {"type": "fixed", "value": 0}}. Keys are short ("Kphi") or Chrono names ("Bekker Kphi").
// Throws InputError naming the file, key, value and allowed range.
Priors load_priors(const std::string& path);

// One prior from its JSON object ({"type": "uniform", "lower": .., "upper": ..}, normal/lognormal
// with "mean" and "sd", or fixed with "value"): fields the file leaves out keep `base`'s values;
// bounds and a fixed value must lie in `allowed`. The reader of every priors file (SCM parameters
// here, vehicle parameters in calibrate-rom). Throws InputError naming path, key, value and range.
Prior parse_prior(const nlohmann::json& spec, const std::string& path, const std::string& key, const Range& allowed,
                  const Prior& base);

}  // namespace terracal::bayes
