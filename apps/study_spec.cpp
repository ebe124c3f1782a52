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
#include "rom/rom_vehicle.hpp"
#include "rom/rom_vehicle_json.hpp"
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
                "slip": [-0.5, -0.2, 0, 0.2, 0.5, 0.8, 0.95], "standstill": true,
                "drop-height": [0.05, 0.2, 0.5, 1]}},
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
    "knobs": {{"spacing": [0.06, 0.05, 0.04, 0.03], "h-over-d0": [1.2, 1.3, 1.4, 1.5], "step": [4e-4, 2e-4, 1e-4]}},
    "sweeps": {{"step": [2e-5, 5e-5, 1e-4, 2e-4, 5e-4, 1e-3], "gravity": {}, "stiffness": {},
                "slip": [-0.5, 0, 0.5, 0.95], "standstill": true, "drop-height": [0.05, 0.1, 0.2]}},
    "effects": {{"no_hourglass_damping": {{"hourglass-damping": 0}},
                 "no_hourglass_stiffness": {{"hourglass-stiffness": 0}},
                 "neither": {{"hourglass-damping": 0, "hourglass-stiffness": 0}}}}}})",
                                 kWheel, kCrmSoil, kGravities, kStiffness));
}

// The bevameter rig: plate tests (a 0.2 m plate to 0.2 m, as studies/bevameter_cost ran them),
// compared on their loading curves.
Json default_bevameter(StudySolver solver) {
  if (solver == StudySolver::kCrm)
    return Json::parse(fmt::format(R"({{
    "soil": {},
    "options": {{"test": "plate", "plates": [0.2], "max-sinkage": 0.2, "cache": ""}},
    "knobs": {{"spacing": [0.04, 0.03, 0.02]}},
    "effects": {{"no_hourglass_stiffness": {{"hourglass-stiffness": 0}}}}}})",
                                   kCrmSoil));
  return Json::parse(fmt::format(R"({{
    "soil": {},
    "options": {{"test": "plate", "plates": [0.2], "max-sinkage": 0.2}},
    "knobs": {{"grid": [0.04, 0.02, 0.01, 0.005, 0.0025]}},
    "effects": {{"none": {{"scm-effects": "none"}}, "elastic_unloading": {{"scm-effects": ["damping", "elastic_unloading"]}}}}}})",
                                 kDrySand));
}

// The step steer of results/rom_accuracy_cost (ISO 7401: 0.15 at 1 s, 20 m/s, 5 s).
constexpr const char* kStepSteer =
    R"({"type": "step_steer", "steering": 0.15, "step_time": 1, "initial_speed": 20, "end_time": 5})";

Json default_rom() {
  return Json::parse(fmt::format(R"({{
    "vehicle": "hmmwv", "maneuver": {},
    "options": {{"model": "24dof"}},
    "reference": {{"integrator": "cvodes", "rtol": 1e-10}},
    "knobs": {{"step": [0.004, 0.002, 0.001, 0.0005, 0.00025], "model": ["11dof", "18dof"],
               "integrator": [{{"integrator": "cvodes", "rtol": 1e-4}}, {{"integrator": "cvodes", "rtol": 1e-6}},
                              {{"integrator": "cvodes", "rtol": 1e-8}}]}},
    "sweeps": {{"step": [0.001, 0.002, 0.004, 0.006, 0.008, 0.01], "gravity": [9.81, 3.71, 1.62, 0.1],
                "friction": [0.05, 0.2, 0.5, 1, 2]}},
    "effects": {{"no_tire_relaxation": {{"vehicle-effects": ["torque_converter", "roll", "rolling_resistance"]}},
                 "no_torque_converter": {{"vehicle-effects": ["tire_relaxation", "roll", "rolling_resistance"]}},
                 "no_rolling_resistance": {{"vehicle-effects": ["tire_relaxation", "torque_converter", "roll"]}}}}}})",
                                 kStepSteer));
}

Json default_vehicle() {
  return Json::parse(fmt::format(R"({{
    "vehicle": "hmmwv", "maneuver": {},
    "options": {{}},
    "reference": {{"rtol": 1e-8}},
    "knobs": {{"rtol": [1e-3, 1e-4, 1e-5, 1e-6], "step": [0.02, 0.01, 0.005]}},
    "sweeps": {{"mu": [0.05, 0.2, 0.5, 1, 2], "step": [0.01, 0.05, 0.1]}},
    "effects": {{}}}})",
                                 kStepSteer));
}

// The options a study sets itself: its scene's and --out.
const std::set<std::string> kStudySets = {"terrain", "solver", "wheel", "scm",  "soil", "out", "help", "gravity",
                                          "no-plots", "vehicle", "maneuver", "inputs"};

bool wheel_rig(StudySolver s) { return s == StudySolver::kCrm || s == StudySolver::kScm || s == StudySolver::kWongReece; }

// A knob's values: numbers, names (a model, an integrator) or objects of options set together (an
// integrator with its tolerance), non-empty, none twice.
std::vector<Json> values(const std::string& spec, const std::string& key, const Json& v) {
  if (!v.is_array() || v.empty())
    throw InputError(fmt::format("{}: key '{}': expected a non-empty list, found {}", spec, key, excerpt(v.dump())));
  auto plain = [](const Json& x) { return x.is_string() || (x.is_number() && std::isfinite(x.get<double>())); };
  std::vector<Json> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const bool object = v[i].is_object() && !v[i].empty() &&
                        std::all_of(v[i].begin(), v[i].end(), [&](const Json& x) { return plain(x); });
    if (!(plain(v[i]) || object))
      throw InputError(fmt::format("{}: key '{}[{}]': expected a number, a name or an object of options (each a "
                                   "number or a name), found {}",
                                   spec, key, i, excerpt(v[i].dump())));
    if (std::count(out.begin(), out.end(), v[i]))
      throw InputError(fmt::format("{}: key '{}[{}]': {} appears twice", spec, key, i, v[i].dump()));
    out.push_back(v[i]);
  }
  return out;
}

std::string text_of(const Json& v) { return v.is_string() ? v.get<std::string>() : fmt::format("{}", v.get<double>()); }

// A knob's value as the report shows it, joined by SEP: an object's values, less those the knob's
// name already says ("24dof_cvodes" with {"model": "24dof", "integrator": "cvodes", "rtol": 1e-6}: 1e-06).
std::string value_text(const std::string& knob, const Json& v, const char* sep = " ") {
  if (!v.is_object()) return text_of(v);
  std::string t;
  const std::string words = "_" + knob + "_";
  for (const auto& [k, x] : v.items())
    if (words.find("_" + text_of(x) + "_") == std::string::npos) t += (t.empty() ? "" : sep) + text_of(x);
  return t.empty() ? "as named" : t;
}

// Sets knob K's value in the options O: the option K, or each option of an object.
void apply_knob(Json& o, const std::string& k, const Json& v) {
  if (!v.is_object()) {
    o[k] = v;
    return;
  }
  for (const auto& [ok, ov] : v.items()) o[ok] = ov;
}

// A part of the scene at KEY: inline (an object), a file relative to the spec, or (vehicle) a preset.
Json scene_part(const std::string& spec, const std::string& key, const Json& v) {
  if (v.is_object()) return v;
  if (key == "vehicle" && v.is_string() && fs::path(v.get<std::string>()).extension() != ".json")
    return v;  // a preset: the command checks its name
  const std::string file = spec_file(spec, key, v);
  return Json::parse(read_json_file(file, key + " file").dump());
}

// The scene's soil option: --soil (a CRM material) or --scm (an SCM set).
const char* soil_option(StudySolver s) { return s == StudySolver::kCrm ? "soil" : "scm"; }

// The soil with its stiffness scaled: Kphi of an SCM set, E of a CRM material.
Json scaled_soil(const StudySpec& s, const Json& soil, double factor) {
  Json out = soil;
  if (s.solver == StudySolver::kCrm)
    out["young_modulus"] = factor * soil.at("young_modulus").get<double>();
  else
    out["Soil parameters"]["Bekker Kphi"] = factor * soil.at("Soil parameters").at("Bekker Kphi").get<double>();
  return out;
}

// Checks the scene before any job: the wheel and the soil as the wheel command reads them (a vehicle
// and a manoeuvre are checked by their command when it runs).
void check_scene(const StudySpec& s, const Json& m) {
  if (!wheel_rig(s.solver)) {
    for (const char* k : {"vehicle", "maneuver"})
      if (!(m[k].is_object() || m[k].is_string()))
        throw InputError(fmt::format("{}: key '{}': expected an object, a file or (vehicle) a preset", s.source, k));
    return;
  }
  if (s.rig != "bevameter") rigs::parse_wheel(nlohmann::json::parse(m["wheel"].dump()), s.source + ": key 'wheel'");
  const nlohmann::json plain = nlohmann::json::parse(m["soil"].dump());
  if (s.solver == StudySolver::kCrm) {
    parse_crm_soil(plain, s.source + ": key 'soil'");
  } else {
    if (!plain.contains("Soil parameters"))
      throw InputError(fmt::format("{}: key 'soil': an SCM set needs the object 'Soil parameters' (Chrono SCM JSON)",
                                   s.source));
    lowfi::parse_scm_soil(plain["Soil parameters"], s.source + ": key 'soil'");
  }
}

// The scene of the base: option -> content.
Json base_scene(const StudySpec& s) {
  if (s.rig == "bevameter") return Json{{soil_option(s.solver), s.merged["soil"]}};
  if (wheel_rig(s.solver)) return Json{{"wheel", s.merged["wheel"]}, {soil_option(s.solver), s.merged["soil"]}};
  return Json{{"vehicle", s.merged["vehicle"]}, {"maneuver", s.merged["maneuver"]}};
}

StudyRun run_of(const std::string& group, const std::string& label, const Json& value, const Json& options,
                const Json& scene, bool reference = false, const std::string& shown = "") {
  StudyRun r{group,   label, value.is_number() ? value.get<double>() : 0.0,
             !shown.empty() ? shown : value.is_null() ? "" : text_of(value),
             options, scene, reference};
  return r;
}

void add_knob_runs(StudySpec& s, const Json& knobs, const Json& base, const Json& scene) {
  const std::string command = study_command(s);
  if (!knobs.is_object() || knobs.empty())
    throw InputError(fmt::format("{}: key 'knobs': expected an object of knob -> values (coarse to fine)", s.source));
  // The reference: the spec's own, or every knob at its finest (the last value).
  const bool given = s.merged.contains("reference");
  Json finest = base;
  if (given) {
    if (!s.merged["reference"].is_object())
      throw InputError(fmt::format("{}: key 'reference': expected an object of options", s.source));
    check_command_options(s.source, "reference.", command, s.merged["reference"], kStudySets);
    for (const auto& [k, v] : s.merged["reference"].items()) finest[k] = v;
  } else {
    for (const auto& [k, v] : knobs.items()) apply_knob(finest, k, values(s.source, "knobs." + k, v).back());
  }
  check_command_options(s.source, given ? "reference." : "knobs.", command, finest, kStudySets);
  s.runs.push_back(run_of("reference", "reference", Json(), finest, scene, true));
  for (const auto& [k, v] : knobs.items()) {
    if (k.empty() || k.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_-") != std::string::npos)
      throw InputError(fmt::format("{}: key 'knobs.{}': a knob's name may hold a-z, 0-9, '_' and '-' only (it names "
                                   "folders)",
                                   s.source, k));
    const std::vector<Json> list = values(s.source, "knobs." + k, v);
    for (std::size_t i = 0; i + (given ? 0 : 1) < list.size(); ++i) {  // without `reference`, the last is it
      Json o = given ? base : finest, own;
      apply_knob(o, k, list[i]);
      apply_knob(own, k, list[i]);
      check_command_options(s.source, fmt::format("knobs.{}[{}]: ", k, i), command, own, kStudySets);
      s.runs.push_back(run_of(k, k + "_" + value_text(k, list[i], "_"), list[i], o, scene, false, value_text(k, list[i])));
    }
  }
}

// One sweep value's options and scene: gravity, stiffness, slip and standstill are the study's own;
// any other name is an option of the command.
void sweep_value(const StudySpec& s, const std::string& k, double x, Json& o, Json& scene) {
  const std::string key = "sweeps." + k;
  const std::string command = study_command(s);
  if (k == "gravity") {
    if (!(x > 0 && x <= 100))
      throw InputError(fmt::format("{}: key '{}': value {} is not a gravity in (0, 100] m/s^2", s.source, key, x));
    if (s.solver == StudySolver::kVehicle)
      throw InputError(fmt::format("{}: key '{}': the full vehicle runs at Earth's gravity only", s.source, key));
    if (s.solver == StudySolver::kCrm) scene["soil"]["gravity"] = Json::array({0.0, 0.0, -x});
    else if (s.solver == StudySolver::kRom) o["gravity"] = x;
    else o["gravity"] = Json::array({0.0, 0.0, -x});
    if (s.solver == StudySolver::kRom) check_command_options(s.source, key + ": ", command, Json{{"gravity", x}}, {});
  } else if (k == "stiffness") {
    if (!wheel_rig(s.solver))
      throw InputError(fmt::format("{}: key '{}': a soil's stiffness; the {} solver runs on rigid ground", s.source,
                                   key, study_solver_name(s.solver)));
    if (!(x > 0)) throw InputError(fmt::format("{}: key '{}': factor {} must be positive", s.source, key, x));
    scene[soil_option(s.solver)] = scaled_soil(s, scene[soil_option(s.solver)], x);
  } else if (k == "slip") {
    if (!wheel_rig(s.solver))
      throw InputError(fmt::format("{}: key '{}': the wheel's slip; not a {} setting", s.source, key,
                                   study_solver_name(s.solver)));
    o["slips"] = Json::array({x});
    check_command_options(s.source, key + ": ", command, Json{{"slips", o["slips"]}}, kStudySets);
  } else {
    if (k == "drop-height" && s.solver == StudySolver::kWongReece)
      throw InputError(fmt::format("{}: key '{}': Wong-Reece is a steady model (no fall, no impact); drops run on "
                                   "scm and crm",
                                   s.source, key));
    o[k] = x;
    check_command_options(s.source, key + ": ", command, Json{{k, x}}, kStudySets);
  }
}

void add_sweep_runs(StudySpec& s, const Json& sweeps, const Json& base, const Json& scene) {
  if (!sweeps.is_object() || sweeps.empty())
    throw InputError(fmt::format("{}: key 'sweeps': expected an object of sweep -> values", s.source));
  s.runs.push_back(run_of("base", "base", Json(), base, scene, true));
  for (const auto& [k, v] : sweeps.items()) {
    if (k == "standstill") {
      if (!v.is_boolean())
        throw InputError(fmt::format("{}: key 'sweeps.standstill': expected true or false, found {}", s.source,
                                     excerpt(v.dump())));
      if (!wheel_rig(s.solver))
        throw InputError(fmt::format("{}: key 'sweeps.standstill': the wheel rig's; give a manoeuvre from rest "
                                     "instead",
                                     s.source));
      if (!v.get<bool>()) continue;
      Json o = base, sc = scene;
      sc["wheel"]["angular_velocity"] = 0.0;
      o["slips"] = Json::array({0.0});
      s.runs.push_back(run_of("standstill", "standstill", Json(), o, sc));
      continue;
    }
    for (const Json& x : values(s.source, "sweeps." + k, v)) {
      if (!x.is_number())
        throw InputError(fmt::format("{}: key 'sweeps.{}': {} is not a number", s.source, k, x.dump()));
      Json o = base, sc = scene;
      sweep_value(s, k, x.get<double>(), o, sc);
      s.runs.push_back(run_of(k, k + "_" + text_of(x), x, o, sc));
    }
  }
}

// A vehicle's JSON for an effects variant: the preset's or file's, with its effects replaced.
Json vehicle_with_effects(const StudySpec& s, const std::string& key, const Json& vehicle, const Json& effects) {
  if (!effects.is_array())
    throw InputError(fmt::format("{}: key '{}': expected a list of effect names, found {}", s.source, key,
                                 excerpt(effects.dump())));
  for (const auto& e : effects)
    if (!e.is_string() || std::none_of(std::begin(rom::kRomEffectNames), std::end(rom::kRomEffectNames),
                                       [&](const char* n) { return e.get<std::string>() == n; }))
      throw InputError(fmt::format("{}: key '{}': unknown effect {}; expected names among {}", s.source, key, e.dump(),
                                   fmt::join(rom::kRomEffectNames, ", ")));
  Json v = vehicle;
  if (vehicle.is_string()) {
    const std::string text = rom::rom_preset_json(vehicle.get<std::string>());
    if (text.empty())
      throw InputError(fmt::format("{}: key 'vehicle': '{}' is no preset (hmmwv, sedan)", s.source,
                                   vehicle.get<std::string>()));
    v = Json::parse(text);
  }
  v["effects"] = effects;
  return v;
}

void add_effect_runs(StudySpec& s, const Json& effects, const Json& base, const Json& scene) {
  if (!effects.is_object() || effects.empty())
    throw InputError(fmt::format("{}: the {} solver has no effects to switch (key 'effects' is empty)", s.source,
                                 study_solver_name(s.solver)));
  s.runs.push_back(run_of("base", "base", Json(), base, scene, true));
  for (const auto& [name, opts] : effects.items()) {
    const std::string key = "effects." + name;
    if (name.empty() || name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_-") != std::string::npos)
      throw InputError(fmt::format("{}: key '{}': a variant's name may hold a-z, 0-9, '_' and '-' only", s.source, key));
    if (!opts.is_object() || opts.empty())
      throw InputError(fmt::format("{}: key '{}': expected an object of options, found {}", s.source, key,
                                   excerpt(opts.dump())));
    Json o = base, sc = scene, own = opts;
    if (own.contains("vehicle-effects")) {  // the ROM's effects live in its vehicle file
      if (s.solver != StudySolver::kRom)
        throw InputError(fmt::format("{}: key '{}.vehicle-effects': only for the rom solver", s.source, key));
      sc["vehicle"] = vehicle_with_effects(s, key + ".vehicle-effects", scene["vehicle"], own["vehicle-effects"]);
      own.erase("vehicle-effects");
    }
    check_command_options(s.source, key + ".", study_command(s), own, kStudySets);
    for (const auto& [k, v] : own.items()) o[k] = v;
    s.runs.push_back(run_of(name, name, Json(), o, sc));
  }
}

}  // namespace

std::string study_kind_name(StudyKind k) { return kStudyKinds[static_cast<int>(k)]; }
std::string study_solver_name(StudySolver s) { return kStudySolvers[static_cast<int>(s)]; }
std::string study_command(StudySolver s) {
  return wheel_rig(s) ? "wheel" : s == StudySolver::kRom ? "rom" : "vehicle";
}

std::string study_command(const StudySpec& s) { return s.rig == "bevameter" ? "bevameter" : study_command(s.solver); }

Json default_study_spec(StudySolver solver, const std::string& rig) {
  if (rig == "bevameter") return default_bevameter(solver);
  switch (solver) {
    case StudySolver::kCrm:
      return default_crm();
    case StudySolver::kScm:
      return default_scm();
    case StudySolver::kWongReece:
      return default_wong_reece();
    case StudySolver::kRom:
      return default_rom();
    case StudySolver::kVehicle:
      return default_vehicle();
  }
  return {};
}

StudySpec read_study_spec(StudyKind kind, StudySolver solver, const std::string& path) {
  StudySpec s;
  s.kind = kind;
  s.solver = solver;
  s.source = path.empty() ? fmt::format("the default {} spec", study_solver_name(solver)) : path;
  Json j;
  if (!path.empty()) {
    j = Json::parse(read_json_file(path, "study spec").dump());
    if (!j.is_object()) throw InputError(fmt::format("{}: expected a JSON object", path));
    if (j.contains("rig")) {
      if (!(j["rig"] == "wheel" || j["rig"] == "bevameter") ||
          !(solver == StudySolver::kCrm || solver == StudySolver::kScm))
        throw InputError(fmt::format("{}: key 'rig': {} is no rig of the {} solver (crm and scm: \"wheel\" or "
                                     "\"bevameter\")",
                                     path, excerpt(j["rig"].dump()), study_solver_name(solver)));
      s.rig = j["rig"].get<std::string>();
      if (s.rig == "bevameter" && kind == StudyKind::kStability)
        throw InputError(fmt::format("{}: key 'rig': the stability study runs the wheel rig (its verdicts are a "
                                     "wheel's); the bevameter has accuracy-cost and effects",
                                     path));
    }
  }
  s.merged = default_study_spec(solver, s.rig);
  const std::set<std::string> keys =
      s.rig == "bevameter" ? std::set<std::string>{"rig", "soil", "options", "knobs", "reference", "effects"}
      : wheel_rig(solver)  ? std::set<std::string>{"rig",       "wheel",  "soil",   "options",
                                                  "knobs",     "reference", "sweeps", "effects"}
                           : std::set<std::string>{"vehicle", "maneuver", "options", "knobs", "reference", "sweeps",
                                                   "effects"};
  if (!path.empty()) {
    refuse_unknown(path, "", j, keys);
    for (const auto& [k, v] : j.items()) {
      if (k == "options") {
        if (!v.is_object()) throw InputError(fmt::format("{}: key 'options': expected an object", path));
        for (const auto& [o, x] : v.items()) s.merged["options"][o] = x;  // over the default's, key by key
      } else if (k == "wheel" || k == "soil" || k == "vehicle" || k == "maneuver") {
        s.merged[k] = scene_part(path, k, v);
      } else if (k != "rig") {
        s.merged[k] = v;
      }
    }
  }
  check_scene(s, s.merged);
  const Json& base = s.merged["options"];
  check_command_options(s.source, "options.", study_command(s), base, kStudySets);
  const Json scene = base_scene(s);
  switch (kind) {
    case StudyKind::kAccuracyCost:
      add_knob_runs(s, s.merged["knobs"], base, scene);
      break;
    case StudyKind::kStability:
      add_sweep_runs(s, s.merged["sweeps"], base, scene);
      break;
    case StudyKind::kEffects:
      add_effect_runs(s, s.merged["effects"], base, scene);
      break;
  }
  return s;
}

namespace {
std::string content_hash(const std::string& text) {
  Fnv1a64 h;
  h.add(text);
  return h.hex();
}
}  // namespace

std::vector<CampaignJob> study_jobs(const StudySpec& s) {
  std::vector<CampaignJob> jobs;
  const std::string stage = study_kind_name(s.kind);
  for (const StudyRun& r : s.runs) {
    CampaignJob j{"", stage, r.label, "", study_command(s), {}, {}, 0, {}, {}};
    if (s.rig == "bevameter") j.args = {"--solver", study_solver_name(s.solver)};
    else if (wheel_rig(s.solver)) j.args = {"--terrain", study_solver_name(s.solver)};
    // Every scene file under its content's hash: runs that share a soil share its file.
    for (const auto& [option, content] : r.scene.items()) {
      if (content.is_string()) {  // a preset
        j.args.insert(j.args.end(), {"--" + option, content.get<std::string>()});
        continue;
      }
      const std::string text = content.dump(2) + "\n";
      const std::string file = "inputs/" + option + "-" + content_hash(text) + ".json";
      j.writes.push_back({file, text});
      j.args.insert(j.args.end(), {"--" + option, "@out/" + file});
    }
    j.args.push_back("--no-plots");
    for (auto& w : command_option_words(j.command, r.options)) j.args.push_back(std::move(w));
    add_job(jobs, j, {});
  }
  return jobs;
}

}  // namespace terracal::app
