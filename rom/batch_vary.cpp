#include "rom/batch_vary.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <set>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "core/json_file.hpp"
#include "core/json_object.hpp"
#include "core/rng.hpp"
#include "core/text_check.hpp"
#include "rom/rom_vehicle_json.hpp"

namespace terracal::rom {

namespace {

constexpr double kMax = std::numeric_limits<double>::max();
constexpr double kHalfPi = 1.5707963267948966;

// The catalogue: its order gives each parameter its random stream, so never reorder it; append.
enum ParamId : int {
  kMass,
  kCgHeight,
  kCgToFront,
  kYawInertia,
  kRollInertia,
  kMaxSteer,
  kFriction,
  kGravity,
  kDragArea,
  kRollStiffnessFront,
  kRollStiffnessRear,
  kRollDampingFront,
  kRollDampingRear,
  kMaxBrakeTorque,
  kTireCorneringScale,
  kTireLongitudinalScale,
  kTorqueScale,
  kTireCorneringScaleFront,
  kTireCorneringScaleRear,
  kRollingResistance,
  kRollStiffnessTotal,
  kRollStiffnessFrontShare,
  kParamCount
};

struct ParamInfo {
  const char* name;
  const char* unit;  // "-" for a factor
  Range range;       // the vehicle reader's range where it reads the value
};

// Range's unit is left empty for factors: "(0, 100]" reads better than "(0, 100] -".
const ParamInfo kParams[kParamCount] = {
    {"mass", "kg", {0, 1e7, true, false, "kg"}},
    {"cg_height", "m", {0, 100, true, false, "m"}},
    {"cg_to_front", "m", {0, 100, true, false, "m"}},
    {"yaw_inertia", "kg m^2", {0, 1e9, true, false, "kg m^2"}},
    {"roll_inertia", "kg m^2", {0, 1e9, true, false, "kg m^2"}},
    {"max_steer", "rad", {0, kHalfPi, true, true, "rad"}},
    {"friction", "-", {0, 10, true, false, ""}},
    {"gravity", "m/s^2", {0, 100, true, false, "m/s^2"}},
    {"drag_area", "m^2", {0, 1e3, false, false, "m^2"}},
    {"roll_stiffness_front", "N m/rad", {0, 1e12, true, false, "N m/rad"}},
    {"roll_stiffness_rear", "N m/rad", {0, 1e12, true, false, "N m/rad"}},
    {"roll_damping_front", "N m s/rad", {0, 1e12, false, false, "N m s/rad"}},
    {"roll_damping_rear", "N m s/rad", {0, 1e12, false, false, "N m s/rad"}},
    {"max_brake_torque", "N m", {0, 1e7, false, false, "N m"}},
    {"tire_cornering_scale", "-", {0, 100, true, false, ""}},
    {"tire_longitudinal_scale", "-", {0, 100, true, false, ""}},
    {"torque_scale", "-", {0, 100, true, false, ""}},
    {"tire_cornering_scale_front", "-", {0, 100, true, false, ""}},
    {"tire_cornering_scale_rear", "-", {0, 100, true, false, ""}},
    {"rolling_resistance", "-", {0, 1, false, false, ""}},
    {"roll_stiffness_total", "N m/rad", {0, 2e12, true, false, "N m/rad"}},
    {"roll_stiffness_front_share", "-", {0, 1, true, true, ""}},
};

int param_id(const std::string& name) {
  for (int k = 0; k < kParamCount; ++k)
    if (name == kParams[k].name) return k;
  return -1;
}

int known_param_id(const std::string& name) {
  const int k = param_id(name);
  if (k < 0) throw InputError(fmt::format("unknown --vary parameter '{}'", name));
  return k;
}

std::string known_list() {
  std::string s;
  for (const auto& p : kParams) s += (s.empty() ? "" : ", ") + std::string(p.name);
  return s;
}

// "2100 kg", "0.8" (a factor has no unit).
std::string with_unit(double x, const char* unit) {
  return std::string(unit) == "-" ? fmt::format("{}", x) : fmt::format("{} {}", x, unit);
}

void apply(RomVehicle& v, const RomVehicle& base, int id, double x) {
  switch (id) {
    case kMass:
      v.mass = x;
      break;
    case kCgHeight:
      v.cg_height = x;
      break;
    case kCgToFront:
      v.cg_to_front = x;
      v.cg_to_rear = base.wheelbase() - x;
      break;
    case kYawInertia:
      v.yaw_inertia = x;
      break;
    case kRollInertia:
      v.roll_inertia = x;
      break;
    case kMaxSteer:
      v.max_steer = x;
      break;
    case kFriction:
      v.friction = x;
      break;
    case kGravity:
      v.gravity = x;
      break;
    case kDragArea:
      v.drag_area = x;
      break;
    case kRollStiffnessFront:
      v.roll_stiffness[0] = x;
      break;
    case kRollStiffnessRear:
      v.roll_stiffness[1] = x;
      break;
    case kRollDampingFront:
      v.roll_damping[0] = x;
      break;
    case kRollDampingRear:
      v.roll_damping[1] = x;
      break;
    case kMaxBrakeTorque:
      v.powertrain.max_brake_torque = x;
      break;
    case kTireCorneringScale:
      for (int a = 0; a < 2; ++a)
        for (int l = 0; l < 2; ++l) v.tire[a].y[l].df0 = x * base.tire[a].y[l].df0;
      break;
    case kTireLongitudinalScale:
      for (int a = 0; a < 2; ++a)
        for (int l = 0; l < 2; ++l) v.tire[a].x[l].df0 = x * base.tire[a].x[l].df0;
      break;
    case kTireCorneringScaleFront:
    case kTireCorneringScaleRear: {
      const int a = id == kTireCorneringScaleFront ? 0 : 1;
      for (int l = 0; l < 2; ++l) v.tire[a].y[l].df0 = x * base.tire[a].y[l].df0;
      break;
    }
    case kRollingResistance:
      for (auto& t : v.tire) t.rolling_resistance = x;
      break;
    // The sum and the front share of the roll stiffness: each keeps the other as v has it, so
    // the two give the same vehicle in either order.
    case kRollStiffnessTotal: {
      const double share = v.roll_stiffness[0] / (v.roll_stiffness[0] + v.roll_stiffness[1]);
      v.roll_stiffness[0] = share * x;
      v.roll_stiffness[1] = (1 - share) * x;
      break;
    }
    case kRollStiffnessFrontShare: {
      const double total = v.roll_stiffness[0] + v.roll_stiffness[1];
      v.roll_stiffness[0] = x * total;
      v.roll_stiffness[1] = (1 - x) * total;
      break;
    }
    case kTorqueScale:
      for (int i = 0; i < base.powertrain.max_torque.n; ++i)
        v.powertrain.max_torque.y[i] = x * base.powertrain.max_torque.y[i];
      break;
    default:
      break;
  }
}

// Why value x of parameter id cannot be used on its own ("" when it can): outside the range, or
// (cg_to_front) no wheelbase left behind the CG.
std::string range_problem(int id, double x, const RomVehicle& base) {
  const ParamInfo& p = kParams[id];
  if (!(std::isfinite(x) && p.range.contains(x))) return fmt::format("is outside the allowed range {}", p.range.text());
  if (id == kCgToFront && !(base.wheelbase() - x > 0))
    return fmt::format("leaves cg_to_rear = wheelbase {} m - {} m = {} m, which must be positive", base.wheelbase(), x,
                       base.wheelbase() - x);
  return {};
}

// Explicit fused multiply-adds: the values do not depend on whether the compiler contracts a * b + c
// (the rom library is built with FMA where the CPU has it), so a seed gives the same vehicles on
// every build.
double draw(const VaryParameter& p, Rng& rng) {
  switch (p.distribution) {
    case VaryDistribution::kNormal:
      return std::fma(p.b, rng.normal(), p.a);
    case VaryDistribution::kLognormal:
      return std::exp(std::fma(p.b, rng.normal(), p.a));
    case VaryDistribution::kUniform:
      return std::fma(p.b - p.a, rng.uniform(), p.a);
  }
  return 0.0;
}

const char* narrower_hint(VaryDistribution d) {
  switch (d) {
    case VaryDistribution::kNormal:
      return "a smaller sd, or a lognormal or uniform one that stays in range";
    case VaryDistribution::kLognormal:
      return "a smaller sigma";
    case VaryDistribution::kUniform:
      return "low and high within the values the parameter allows";
  }
  return "";
}

}  // namespace

const std::vector<std::string>& vary_parameter_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto& p : kParams) n.emplace_back(p.name);
    return n;
  }();
  return names;
}

std::string vary_parameter_unit(const std::string& name) { return kParams[known_param_id(name)].unit; }

Range vary_parameter_range(const std::string& name) { return kParams[known_param_id(name)].range; }

std::string vary_distribution_text(const VaryParameter& p) {
  switch (p.distribution) {
    case VaryDistribution::kNormal:
      return fmt::format("normal(mean {}, sd {})", p.a, p.b);
    case VaryDistribution::kLognormal:
      return fmt::format("lognormal(mu {}, sigma {})", p.a, p.b);
    case VaryDistribution::kUniform:
      return fmt::format("uniform(low {}, high {})", p.a, p.b);
  }
  return "";
}

std::string overlapping_parameters(const std::vector<std::string>& names) {
  // Each pair: a parameter and those that set some of the same values (the later one would win).
  static const std::pair<const char*, std::vector<const char*>> kOverlaps[] = {
      {"roll_stiffness_total", {"roll_stiffness_front", "roll_stiffness_rear"}},
      {"roll_stiffness_front_share", {"roll_stiffness_front", "roll_stiffness_rear"}},
      {"tire_cornering_scale", {"tire_cornering_scale_front", "tire_cornering_scale_rear"}},
  };
  const auto has = [&](const char* n) { return std::find(names.begin(), names.end(), n) != names.end(); };
  for (const auto& [a, others] : kOverlaps)
    for (const char* b : others)
      if (has(a) && has(b))
        return fmt::format("'{}' and '{}' set the same vehicle values; give one or the other", a, b);
  return {};
}

void apply_vary_parameter(RomVehicle& v, const RomVehicle& base, const std::string& name, double value) {
  apply(v, base, known_param_id(name), value);
}

VarySpec vary_from_json(const nlohmann::json& j, const std::string& source) {
  JsonObject root(j, source, "");
  if (j.empty())
    throw InputError(fmt::format("{}: names no parameter to vary; expected keys among: {}", source, known_list()));
  VarySpec spec;
  spec.source = source;
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& key = it.key();
    const int id = param_id(key);
    if (id < 0)
      root.fail(key, fmt::format("unknown parameter (value {}); expected one of: {}", shorten(it.value().dump()),
                                 known_list()));
    JsonObject d = root.object(key);
    if (!d.has("distribution"))
      d.fail("distribution", "is required but missing; expected one of: normal, lognormal, uniform");
    VaryParameter p;
    p.name = key;
    const std::string dist = d.string_or("distribution", "", {"normal", "lognormal", "uniform"});
    p.distribution = dist == "normal"      ? VaryDistribution::kNormal
                     : dist == "lognormal" ? VaryDistribution::kLognormal
                                           : VaryDistribution::kUniform;
    const char* first = dist == "normal" ? "mean" : dist == "lognormal" ? "mu" : "low";
    const char* second = dist == "normal" ? "sd" : dist == "lognormal" ? "sigma" : "high";
    // Keys of another distribution first: "sd" in a uniform is better named as such than as a
    // missing "low".
    for (auto k = it.value().begin(); k != it.value().end(); ++k)
      if (k.key() != "distribution" && k.key() != first && k.key() != second)
        d.fail(k.key(), fmt::format("unknown key for a {} distribution (value {}); expected: distribution, {}, {}",
                                    dist, shorten(k.value().dump()), first, second));
    if (p.distribution == VaryDistribution::kUniform) {
      p.a = d.number(first, -kMax, kMax);
      p.b = d.number(second, -kMax, kMax);
      if (!(p.a < p.b))
        d.fail(second, fmt::format("value {} must exceed low = {} (uniform(low, high) needs low < high)", p.b, p.a));
      const Range& r = kParams[id].range;
      if (p.a < r.lo)
        d.fail(first, fmt::format("value {} is below the smallest allowed {} value, {} (allowed range {})", p.a, key,
                                  r.lo, r.text()));
      if (p.b > r.hi)
        d.fail(second, fmt::format("value {} is above the largest allowed {} value, {} (allowed range {})", p.b, key,
                                   r.hi, r.text()));
    } else {
      // exp(mu) must stay finite: |mu| <= 700.
      p.a = p.distribution == VaryDistribution::kNormal ? d.number(first, -kMax, kMax) : d.number(first, -700, 700);
      p.b = d.number(second, -kMax, kMax);
      if (!(p.b > 0))
        d.fail(second, fmt::format("value {} must be positive (the {} of a {} distribution)", p.b, second, dist));
    }
    d.finish();
    spec.parameters.push_back(p);
  }
  root.finish();
  std::vector<std::string> names;
  for (const auto& p : spec.parameters) names.push_back(p.name);
  if (const std::string overlap = overlapping_parameters(names); !overlap.empty())
    throw InputError(fmt::format("{}: {}", source, overlap));
  std::sort(spec.parameters.begin(), spec.parameters.end(),
            [](const VaryParameter& x, const VaryParameter& y) { return x.name < y.name; });
  return spec;
}

VarySpec read_vary(const std::string& path) { return vary_from_json(read_json_file(path, "vary file"), path); }

VaryDraws draw_vehicles(const RomVehicle& base, const VarySpec& spec, long n, std::uint64_t seed,
                        std::uint64_t max_bytes) {
  const std::string& src = spec.source.empty() ? std::string("--vary") : spec.source;
  if (n < 1) throw InputError(fmt::format("{}: the number of vehicles {} must be at least 1", src, n));
  constexpr std::uint64_t per_vehicle = sizeof(RomVehicle);
  if (static_cast<std::uint64_t>(n) > max_bytes / per_vehicle) {
    constexpr double gib = 1024.0 * 1024.0 * 1024.0;
    throw InputError(fmt::format(
        "{}: {} vehicles need {:.3g} GiB for their parameters ({} bytes each), more than the limit of {:.3g} GiB: run "
        "at most {} vehicles per batch (several batches with different seeds) or raise the limit",
        src, n, static_cast<double>(n) * per_vehicle / gib, per_vehicle, static_cast<double>(max_bytes) / gib,
        max_bytes / per_vehicle));
  }

  const std::size_t np = spec.parameters.size(), nv = static_cast<std::size_t>(n);
  std::vector<int> ids(np);
  VaryDraws d;
  for (std::size_t p = 0; p < np; ++p) {
    const VaryParameter& vp = spec.parameters[p];
    ids[p] = param_id(vp.name);
    if (ids[p] < 0)
      throw InputError(fmt::format("{}: key '{}': unknown parameter; expected one of: {}", src, vp.name, known_list()));
    for (std::size_t q = 0; q < p; ++q)
      if (spec.parameters[q].name == vp.name)
        throw InputError(fmt::format("{}: key '{}' is given twice", src, vp.name));
    d.names.push_back(vp.name);
    d.units.emplace_back(kParams[ids[p]].unit);
    d.distributions.push_back(vary_distribution_text(vp));
    // One stream per parameter, numbered by the catalogue: independent of what else is varied.
    Rng rng = Rng::for_stream(seed, static_cast<std::uint64_t>(ids[p]));
    std::vector<double> values(nv);
    for (double& x : values) x = draw(vp, rng);
    d.values.push_back(std::move(values));
  }

  // Build and check every vehicle; the lowest failing index is reported (whatever the threads).
  d.vehicles.resize(nv);
  std::atomic<long> first_bad{n};
  const std::string quiet_source = src;
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    RomVehicle& v = d.vehicles[static_cast<std::size_t>(i)];
    v = base;
    bool ok = true;
    for (std::size_t p = 0; p < np; ++p) {
      const double x = d.values[p][static_cast<std::size_t>(i)];
      ok = ok && range_problem(ids[p], x, base).empty();
      apply(v, base, ids[p], x);
    }
    if (ok) {
      try {
        validate(v, quiet_source);
      } catch (...) {
        ok = false;
      }
    }
    if (!ok) {
      long cur = first_bad.load();
      while (i < cur && !first_bad.compare_exchange_weak(cur, i)) {
      }
    }
  }
  const long bad = first_bad.load();
  if (bad == n) return d;

  // Name the parameter: one out of range, else one that fails validate on its own, else them all.
  const std::size_t b = static_cast<std::size_t>(bad);
  auto refuse = [&](std::size_t p, const std::string& why) {
    const VaryParameter& vp = spec.parameters[p];
    throw InputError(
        fmt::format("{}: key '{}': vehicle {} (of {}, seed {}) drew value {} from {}, which {}; nothing is clipped or "
                    "redrawn: give "
                    "'{}' a narrower distribution ({})",
                    src, vp.name, bad, n, seed, with_unit(d.values[p][b], kParams[ids[p]].unit), d.distributions[p],
                    why, vp.name, narrower_hint(vp.distribution)));
  };
  for (std::size_t p = 0; p < np; ++p) {
    const std::string why = range_problem(ids[p], d.values[p][b], base);
    if (!why.empty()) refuse(p, why);
  }
  const std::string where = fmt::format("{} vehicle {}", src, bad);
  std::string whole_failure;
  try {
    validate(d.vehicles[b], where);
  } catch (const std::exception& e) {
    whole_failure = e.what();
  }
  if (whole_failure.empty())  // cannot happen (the parallel pass found a failure); be safe
    throw InputError(fmt::format("{}: vehicle {} failed its checks", src, bad));
  for (std::size_t p = 0; p < np; ++p) {
    RomVehicle alone = base;
    apply(alone, base, ids[p], d.values[p][b]);
    try {
      validate(alone, where);
    } catch (const std::exception& e) {
      refuse(p, fmt::format("makes a vehicle that fails its checks ({})", e.what()));
    }
  }
  std::string drawn;
  for (std::size_t p = 0; p < np; ++p)
    drawn += fmt::format("{}{} = {}", p ? ", " : "", d.names[p], with_unit(d.values[p][b], kParams[ids[p]].unit));
  throw InputError(fmt::format(
      "{}: vehicle {} (of {}, seed {}) drew {}; together these make a vehicle that fails its checks ({}); nothing is "
      "clipped or redrawn: give these parameters narrower distributions",
      src, bad, n, seed, drawn, whole_failure));
}

double smallest_valid_value(const RomVehicle& base, const std::string& name) {
  const bool longitudinal = name == "tire_longitudinal_scale";
  const bool front = name == "tire_cornering_scale" || name == "tire_cornering_scale_front" || longitudinal;
  const bool rear = name == "tire_cornering_scale" || name == "tire_cornering_scale_rear" || longitudinal;
  double lowest = 0;
  for (int a = 0; a < 2; ++a) {
    if (!(a == 0 ? front : rear)) continue;
    for (int l = 0; l < 2; ++l) {
      const TmeasyCurve& c = longitudinal ? base.tire[a].x[l] : base.tire[a].y[l];
      if (c.df0 > 0 && c.sm > 0) lowest = std::max(lowest, 2.0 * c.fm / (c.sm * c.df0));
    }
  }
  return lowest;
}

}  // namespace terracal::rom
