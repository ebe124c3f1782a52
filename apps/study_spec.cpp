#include "apps/study_spec.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "apps/job_options.hpp"
#include "core/checksum.hpp"
#include "core/errors.hpp"
#include "core/json_file.hpp"
#include "core/text_check.hpp"
#include "highfi/crm/crm_scene.hpp"
#include "lowfi/scm_soil.hpp"
#include "virtual_bevameter/wheel_rig.hpp"

namespace terracal::app {
namespace fs = std::filesystem;
namespace {

using Json = nlohmann::ordered_json;

// The scene every default shares: the rover wheel of studies/campaign/wheel.json.
constexpr const char* kWheel = R"({"radius": 0.47, "width": 0.25, "mass": 108, "angular_velocity": 1.0})";
// Dry sand (J.Y. Wong, Theory of Ground Vehicles, Table 2.3; Janosi k 0.01 m assumed), as
// studies/campaign/dry_sand_scm.json.
constexpr const char* kDrySand = R"({"Type": "SCM", "Soil parameters": {"Bekker Kc": 990, "Bekker Kphi": 1528430,
  "Bekker n exponent": 1.1, "Mohr cohesive limit": 1040, "Mohr friction limit": 28, "Janosi shear coefficient": 0.01,
  "Elastic stiffness": 4e7, "Damping": 3e4}})";
// The 2022 CRM soil of studies/pipeline/bevameter_soil_2022.json.
constexpr const char* kCrmSoil = R"({"density": 1700, "young_modulus": 1e6, "poisson_ratio": 0.3, "mu_s": 0.7,
  "mu_2": 0.7, "I0": 0.03, "grain_diameter": 0.005, "cohesion": 0, "gravity": [0, 0, -9.81]})";

// Gravities of the mission's hard cases: Earth, Mars, Moon, 0.01 g.
constexpr const char* kGravities = "[9.81, 3.71, 1.62, 0.0981]";
// Stiffness (Kphi, E) over four decades around the soil's own.
constexpr const char* kStiffness = "[0.01, 0.1, 1, 10, 100]";

Json default_scm() {
  return Json::parse(fmt::format(R"({{
    "wheel": {}, "soil": {},
    "options": {{"slips": [0.1, 0.3, 0.5, 0.7], "duration": 2}},
    "knobs": {{"grid": [0.04, 0.02, 0.01, 0.005, 0.0025], "step": [0.004, 0.002, 0.001, 0.0005, 0.00025]}},
    "sweeps": {{"step": [0.0005, 0.001, 0.002, 0.005, 0.01, 0.02, 0.05, 0.1], "gravity": {}, "stiffness": {},
                "slip": [-0.5, -0.2, 0, 0.2, 0.5, 0.8, 0.95], "standstill": true}},
    "effects": {{"none": {{"scm-effects": "none"}},
                 "elastic_unloading": {{"scm-effects": ["damping", "elastic_unloading"]}},
                 "bulldozing": {{"scm-effects": ["damping", "bulldozing"]}},
                 "all": {{"scm-effects": ["damping", "elastic_unloading", "bulldozing"]}}}}}})",
                                 kWheel, kDrySand, kGravities, kStiffness));
}

Json default_wong_reece() {
  return Json::parse(fmt::format(R"({{
    "wheel": {}, "soil": {},
    "options": {{"slips": [0.1, 0.3, 0.5, 0.7]}},
    "knobs": {{"wong-reece-tolerance": [1e-3, 1e-4, 1e-5, 1e-6, 1e-8, 1e-10, 1e-12]}},
    "sweeps": {{"gravity": {}, "stiffness": {}, "slip": [-0.5, -0.2, 0, 0.2, 0.5, 0.8, 0.95]}},
    "effects": {{}}}})",
                                 kWheel, kDrySand, kGravities, kStiffness));
}

Json default_crm() {
  return Json::parse(fmt::format(R"({{
    "wheel": {}, "soil": {},
    "options": {{"slips": [0.2, 0.5], "duration": 1, "spacing": 0.04, "cache": ""}},
    "knobs": {{"spacing": [0.06, 0.05, 0.04, 0.03], "h-over-d0": [1.2, 1.3, 1.4, 1.5]}},
    "sweeps": {{"step": [2e-5, 5e-5, 1e-4, 2e-4, 5e-4, 1e-3], "gravity": {}, "stiffness": {},
                "slip": [-0.5, 0, 0.5, 0.95], "standstill": true}},
    "effects": {{"no_hourglass_damping": {{"hourglass-damping": 0}},
                 "no_hourglass_stiffness": {{"hourglass-stiffness": 0}},
                 "neither": {{"hourglass-damping": 0, "hourglass-stiffness": 0}}}}}})",
                                 kWheel, kCrmSoil, kGravities, kStiffness));
}

// The options a study sets itself.
const std::set<std::string> kStudySets = {"terrain", "wheel", "scm", "soil", "out", "help", "gravity", "no-plots"};

std::string content_hash(const std::string& text) {
  Fnv1a64 h;
  h.add(text);
  return h.hex();
}

// "grid_0.005": names a run's folder.
std::string label_of(const std::string& group, double v) { return fmt::format("{}_{}", group, v); }

// A list of numbers at KEY, non-empty, every one finite.
std::vector<double> numbers(const std::string& spec, const std::string& key, const Json& v) {
  if (!v.is_array() || v.empty())
    throw InputError(fmt::format("{}: key '{}': expected a non-empty list of numbers, found {}", spec, key,
                                 excerpt(v.dump())));
  std::vector<double> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!v[i].is_number() || !std::isfinite(v[i].get<double>()))
      throw InputError(fmt::format("{}: key '{}[{}]': expected a number, found {}", spec, key, i, excerpt(v[i].dump())));
    if (std::count(out.begin(), out.end(), v[i].get<double>()))
      throw InputError(fmt::format("{}: key '{}[{}]': {} appears twice", spec, key, i, v[i].get<double>()));
    out.push_back(v[i].get<double>());
  }
  return out;
}

// The wheel or soil at KEY: inline (an object) or a file relative to the spec.
Json scene_part(const std::string& spec, const std::string& key, const Json& v) {
  if (v.is_object()) return v;
  const std::string file = spec_file(spec, key, v);
  return Json::parse(read_json_file(file, key + " file").dump());
}

// The soil with its stiffness scaled: Kphi of an SCM set, E of a CRM material.
Json scaled_soil(const StudySpec& s, const Json& soil, double factor) {
  Json out = soil;
  if (s.solver == SoilModel::kCrm)
    out["young_modulus"] = factor * soil.at("young_modulus").get<double>();
  else
    out["Soil parameters"]["Bekker Kphi"] = factor * soil.at("Soil parameters").at("Bekker Kphi").get<double>();
  return out;
}

// Checks the scene before any job: the wheel and the soil as the wheel command reads them.
void check_scene(const StudySpec& s, const Json& wheel, const Json& soil) {
  rigs::parse_wheel(nlohmann::json::parse(wheel.dump()), s.source + ": key 'wheel'");
  const nlohmann::json plain = nlohmann::json::parse(soil.dump());
  if (s.solver == SoilModel::kCrm) {
    parse_crm_soil(plain, s.source + ": key 'soil'");
  } else {
    if (!plain.contains("Soil parameters"))
      throw InputError(fmt::format("{}: key 'soil': an SCM set needs the object 'Soil parameters' (Chrono SCM JSON)",
                                   s.source));
    lowfi::parse_scm_soil(plain["Soil parameters"], s.source + ": key 'soil'");
  }
}

void add_knob_runs(StudySpec& s, const Json& knobs, const Json& base, const Json& soil, const Json& wheel) {
  if (!knobs.is_object() || knobs.empty())
    throw InputError(fmt::format("{}: key 'knobs': expected an object of knob -> values (coarse to fine)", s.source));
  Json finest = base;
  for (const auto& [k, v] : knobs.items()) finest[k] = numbers(s.source, "knobs." + k, v).back();
  check_command_options(s.source, "knobs.", "wheel", finest, kStudySets);
  s.runs.push_back({"reference", "reference", 0, finest, soil, wheel, true});
  for (const auto& [k, v] : knobs.items()) {
    const std::vector<double> values = numbers(s.source, "knobs." + k, v);
    for (std::size_t i = 0; i + 1 < values.size(); ++i) {  // the last is the reference's
      Json o = finest;
      o[k] = values[i];
      check_command_options(s.source, fmt::format("knobs.{}[{}]: ", k, i), "wheel", Json{{k, values[i]}}, kStudySets);
      s.runs.push_back({k, label_of(k, values[i]), values[i], o, soil, wheel, false});
    }
  }
}

void add_sweep_runs(StudySpec& s, const Json& sweeps, const Json& base, const Json& soil, const Json& wheel) {
  if (!sweeps.is_object() || sweeps.empty())
    throw InputError(fmt::format("{}: key 'sweeps': expected an object of sweep -> values", s.source));
  s.runs.push_back({"base", "base", 0, base, soil, wheel, true});
  for (const auto& [k, v] : sweeps.items()) {
    if (k == "standstill") {
      if (!v.is_boolean())
        throw InputError(fmt::format("{}: key 'sweeps.standstill': expected true or false, found {}", s.source,
                                     excerpt(v.dump())));
      if (!v.get<bool>()) continue;
      Json w = wheel, o = base;
      w["angular_velocity"] = 0.0;
      o["slips"] = Json::array({0.0});
      s.runs.push_back({"standstill", "standstill", 0, o, soil, w, false});
      continue;
    }
    for (double x : numbers(s.source, "sweeps." + k, v)) {
      Json o = base, so = soil;
      const std::string key = fmt::format("sweeps.{}", k);
      if (k == "gravity") {
        if (!(x > 0 && x <= 100))
          throw InputError(fmt::format("{}: key '{}': value {} is not a gravity in (0, 100] m/s^2", s.source, key, x));
        if (s.solver == SoilModel::kCrm)
          so["gravity"] = Json::array({0.0, 0.0, -x});
        else
          o["gravity"] = Json::array({0.0, 0.0, -x});
      } else if (k == "stiffness") {
        if (!(x > 0)) throw InputError(fmt::format("{}: key '{}': factor {} must be positive", s.source, key, x));
        so = scaled_soil(s, soil, x);
      } else if (k == "slip") {
        o["slips"] = Json::array({x});
      } else {
        o[k] = x;
      }
      const Json own = k == "gravity" && s.solver != SoilModel::kCrm ? Json{{"gravity", o["gravity"]}}
                       : k == "slip"                                 ? Json{{"slips", o["slips"]}}
                       : k == "stiffness" || k == "gravity"          ? Json::object()
                                                                     : Json{{k, x}};
      if (k != "gravity") check_command_options(s.source, key + ": ", "wheel", own, kStudySets);
      s.runs.push_back({k, label_of(k, x), x, o, so, wheel, false});
    }
  }
}

void add_effect_runs(StudySpec& s, const Json& effects, const Json& base, const Json& soil, const Json& wheel) {
  if (!effects.is_object() || effects.empty())
    throw InputError(fmt::format("{}: the {} solver has no effects to switch (key 'effects' is empty)", s.source,
                                 soil_model_name(s.solver)));
  s.runs.push_back({"base", "base", 0, base, soil, wheel, true});
  for (const auto& [name, opts] : effects.items()) {
    if (name.empty() || name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_-") != std::string::npos)
      throw InputError(fmt::format("{}: key 'effects.{}': a variant's name may hold a-z, 0-9, '_' and '-' only",
                                   s.source, name));
    if (!opts.is_object() || opts.empty())
      throw InputError(fmt::format("{}: key 'effects.{}': expected an object of wheel options, found {}", s.source,
                                   name, excerpt(opts.dump())));
    check_command_options(s.source, "effects." + name + ".", "wheel", opts, kStudySets);
    Json o = base;
    for (const auto& [k, v] : opts.items()) o[k] = v;
    s.runs.push_back({name, name, 0, o, soil, wheel, false});
  }
}

}  // namespace

std::string study_kind_name(StudyKind k) { return kStudyKinds[static_cast<int>(k)]; }

Json default_study_spec(SoilModel solver) {
  switch (solver) {
    case SoilModel::kCrm:
      return default_crm();
    case SoilModel::kScm:
      return default_scm();
    case SoilModel::kWongReece:
      return default_wong_reece();
  }
  return {};
}

StudySpec read_study_spec(StudyKind kind, SoilModel solver, const std::string& path) {
  StudySpec s;
  s.kind = kind;
  s.solver = solver;
  s.source = path.empty() ? fmt::format("the default {} spec", soil_model_name(solver)) : path;
  s.merged = default_study_spec(solver);
  if (!path.empty()) {
    const Json j = Json::parse(read_json_file(path, "study spec").dump());
    if (!j.is_object()) throw InputError(fmt::format("{}: expected a JSON object", path));
    refuse_unknown(path, "", j, {"wheel", "soil", "options", "knobs", "sweeps", "effects"});
    for (const auto& [k, v] : j.items()) {
      if (k == "options") {
        if (!v.is_object()) throw InputError(fmt::format("{}: key 'options': expected an object", path));
        for (const auto& [o, x] : v.items()) s.merged["options"][o] = x;  // over the default's, key by key
      } else {
        s.merged[k] = (k == "wheel" || k == "soil") ? scene_part(path, k, v) : v;
      }
    }
  }
  const Json& m = s.merged;
  check_scene(s, m["wheel"], m["soil"]);
  check_command_options(s.source, "options.", "wheel", m["options"], kStudySets);
  switch (kind) {
    case StudyKind::kAccuracyCost:
      add_knob_runs(s, m["knobs"], m["options"], m["soil"], m["wheel"]);
      break;
    case StudyKind::kStability:
      add_sweep_runs(s, m["sweeps"], m["options"], m["soil"], m["wheel"]);
      break;
    case StudyKind::kEffects:
      add_effect_runs(s, m["effects"], m["options"], m["soil"], m["wheel"]);
      break;
  }
  return s;
}

std::vector<CampaignJob> study_jobs(const StudySpec& s) {
  std::vector<CampaignJob> jobs;
  const std::string stage = study_kind_name(s.kind);
  for (const StudyRun& r : s.runs) {
    CampaignJob j{"", stage, r.label, "", "wheel", {"--terrain", soil_model_name(s.solver)}, {}, 0, {}};
    // Every scene file under its content's hash: runs that share a soil share its file.
    const std::string soil_text = r.soil.dump(2) + "\n", wheel_text = r.wheel.dump(2) + "\n";
    const std::string soil_file = "inputs/soil-" + content_hash(soil_text) + ".json";
    const std::string wheel_file = "inputs/wheel-" + content_hash(wheel_text) + ".json";
    j.writes = {{soil_file, soil_text}, {wheel_file, wheel_text}};
    j.args.insert(j.args.end(), {s.solver == SoilModel::kCrm ? "--soil" : "--scm", "@out/" + soil_file, "--wheel",
                                 "@out/" + wheel_file, "--no-plots"});
    for (auto& w : command_option_words("wheel", r.options)) j.args.push_back(std::move(w));
    add_job(jobs, j, {});
  }
  return jobs;
}

}  // namespace terracal::app
