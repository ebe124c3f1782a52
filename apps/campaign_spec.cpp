#include "apps/campaign_spec.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "apps/job_options.hpp"
#include "core/checksum.hpp"
#include "core/errors.hpp"
#include "core/json_file.hpp"
#include "core/text_check.hpp"
#include "terracal_version.hpp"

namespace terracal::app {
namespace fs = std::filesystem;
namespace {

using Json = nlohmann::ordered_json;

// The command each stage runs and the options the campaign sets itself (not allowed in "options").
const std::map<std::string, std::string> kStageCommand = {
    {"bevameter", "bevameter"}, {"calibrate", "calibrate"},     {"wheel", "wheel"},
    {"wheel_reference", "wheel"}, {"wheel_table", "wheel-table"}, {"rom", "rom"}};
const std::set<std::string> kCampaignSets = {"out",   "scm",     "soil", "solver",  "terrain",  "plate",
                                             "shear", "wheel",   "gravity", "test", "help",     "vehicle",
                                             "maneuver", "inputs", "terrain-table", "batch"};

std::string name_of(const std::string& spec, const std::string& key, const Json& o, std::set<std::string>& seen) {
  if (!o.contains("name") || !o["name"].is_string() || o["name"].get<std::string>().empty())
    throw InputError(fmt::format("{}: key '{}.name': expected a non-empty string", spec, key));
  const std::string n = o["name"].get<std::string>();
  if (n.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.") != std::string::npos)
    throw InputError(fmt::format("{}: key '{}.name': '{}' may hold letters, digits, '_', '-' and '.' only "
                                 "(it names folders)",
                                 spec, key, n));
  if (!seen.insert(n).second) throw InputError(fmt::format("{}: key '{}.name': '{}' appears twice", spec, key, n));
  return n;
}

// Every option of a stage is one its command takes, with a value the option accepts: a bad value stops
// the campaign before any job.
void check_stage_options(const std::string& spec, const std::string& stage, const Json& opts) {
  for (const auto& [k, v] : opts.items())
    if (kCampaignSets.count(k))
      throw InputError(fmt::format("{}: key 'options.{}.{}': the campaign sets --{} itself", spec, stage, k, k));
  check_command_options(spec, fmt::format("options.{}.", stage), kStageCommand.at(stage), opts, {});
}

// The vehicles: unique names, a preset or file, a manoeuvre file and one of the spec's wheels.
std::vector<CampaignVehicle> read_vehicles(const std::string& path, const Json& list,
                                           const std::vector<CampaignWheel>& wheels) {
  if (!list.is_array() || list.empty())
    throw InputError(fmt::format("{}: key 'vehicles': expected a non-empty list", path));
  std::vector<CampaignVehicle> out;
  std::set<std::string> names;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Json& o = list[i];
    const std::string key = fmt::format("vehicles[{}]", i);
    if (!o.is_object()) throw InputError(fmt::format("{}: key '{}': expected an object", path, key));
    refuse_unknown(path, key + ".", o, {"name", "vehicle", "maneuver", "wheel"});
    CampaignVehicle v{name_of(path, key, o, names), "", "", ""};
    const Json vehicle = o.value("vehicle", Json());
    if (!vehicle.is_string() || vehicle.get<std::string>().empty())
      throw InputError(fmt::format("{}: key '{}.vehicle': expected a preset (hmmwv, sedan) or a vehicle file", path, key));
    v.vehicle = fs::path(vehicle.get<std::string>()).extension() == ".json" ? spec_file(path, key + ".vehicle", vehicle)
                                                                           : vehicle.get<std::string>();
    v.maneuver = spec_file(path, key + ".maneuver", o.value("maneuver", Json()));
    const Json wheel = o.value("wheel", Json());
    if (!wheel.is_string() || std::none_of(wheels.begin(), wheels.end(), [&](const CampaignWheel& w) {
          return w.name == wheel.get<std::string>();
        }))
      throw InputError(fmt::format("{}: key '{}.wheel': {} is none of the spec's wheels (the tire whose table the "
                                   "vehicle drives on)",
                                   path, key, excerpt(wheel.dump())));
    v.wheel = wheel.get<std::string>();
    out.push_back(v);
  }
  return out;
}

}  // namespace

CampaignSpec read_campaign_spec(const std::string& path) {
  const Json j = Json::parse(read_json_file(path, "campaign spec").dump());
  if (!j.is_object()) throw InputError(fmt::format("{}: expected a JSON object", path));
  refuse_unknown(path, "", j, {"name", "soils", "gravities", "wheels", "vehicles", "stages", "options"});
  CampaignSpec s;
  s.name = j.value("name", fs::path(path).stem().string());
  for (const char* k : {"soils", "gravities", "wheels"})
    if (!j.contains(k) || !j[k].is_array() || j[k].empty())
      throw InputError(fmt::format("{}: key '{}': expected a non-empty list", path, k));
  std::set<std::string> names;
  for (std::size_t i = 0; i < j["soils"].size(); ++i) {
    const Json& o = j["soils"][i];
    const std::string key = fmt::format("soils[{}]", i);
    if (!o.is_object()) throw InputError(fmt::format("{}: key '{}': expected an object", path, key));
    refuse_unknown(path, key + ".", o, {"name", "scm", "crm"});
    CampaignSoil soil{name_of(path, key, o, names), "", ""};
    if (o.contains("scm") == o.contains("crm"))
      throw InputError(fmt::format("{}: key '{}': give exactly one of 'scm' (an SCM set) and 'crm' (a CRM material)",
                                   path, key));
    (o.contains("scm") ? soil.scm : soil.crm) = spec_file(path, key + (o.contains("scm") ? ".scm" : ".crm"),
                                                          o.contains("scm") ? o["scm"] : o["crm"]);
    s.soils.push_back(soil);
  }
  for (std::size_t i = 0; i < j["gravities"].size(); ++i) {
    const Json& g = j["gravities"][i];
    if (!g.is_number() || !(g.get<double>() >= 0.01 && g.get<double>() <= 30))
      throw InputError(fmt::format("{}: key 'gravities[{}]': value {} is not a gravity in [0.01, 30] m/s^2", path, i,
                                   excerpt(g.dump())));
    if (std::count(s.gravities.begin(), s.gravities.end(), g.get<double>()))
      throw InputError(fmt::format("{}: key 'gravities[{}]': {} appears twice", path, i, g.get<double>()));
    s.gravities.push_back(g.get<double>());
  }
  names.clear();
  for (std::size_t i = 0; i < j["wheels"].size(); ++i) {
    const Json& o = j["wheels"][i];
    const std::string key = fmt::format("wheels[{}]", i);
    if (!o.is_object()) throw InputError(fmt::format("{}: key '{}': expected an object", path, key));
    refuse_unknown(path, key + ".", o, {"name", "wheel"});
    const std::string n = name_of(path, key, o, names);
    s.wheels.push_back({n, spec_file(path, key + ".wheel", o.value("wheel", Json()))});
  }
  if (j.contains("vehicles")) s.vehicles = read_vehicles(path, j["vehicles"], s.wheels);
  std::set<std::string> asked;
  if (j.contains("stages")) {
    if (!j["stages"].is_array() || j["stages"].empty())
      throw InputError(fmt::format("{}: key 'stages': expected a non-empty list of {}", path, fmt::join(kCampaignStages, ", ")));
    for (const auto& st : j["stages"]) {
      if (!st.is_string() || !kStageCommand.count(st.get<std::string>()))
        throw InputError(fmt::format("{}: key 'stages': unknown stage {}; expected {}", path, excerpt(st.dump()),
                                     fmt::join(kCampaignStages, ", ")));
      asked.insert(st.get<std::string>());
    }
  } else {  // the soil loop, and the vehicles' stages when the spec has vehicles
    asked.insert(kCampaignStages.begin(), kCampaignStages.end());
    if (s.vehicles.empty()) asked.erase("wheel_table"), asked.erase("rom");
  }
  if (asked.count("calibrate") && !asked.count("bevameter"))
    throw InputError(fmt::format("{}: key 'stages': 'calibrate' needs 'bevameter'", path));
  if (asked.count("wheel") && !asked.count("calibrate"))
    throw InputError(fmt::format("{}: key 'stages': 'wheel' (the calibrated set) needs 'calibrate'", path));
  if (asked.count("wheel_table") && !asked.count("calibrate"))
    throw InputError(fmt::format("{}: key 'stages': 'wheel_table' (of the calibrated set) needs 'calibrate'", path));
  if (asked.count("rom") && !asked.count("wheel_table"))
    throw InputError(fmt::format("{}: key 'stages': 'rom' (a vehicle on the wheel table) needs 'wheel_table'", path));
  if (asked.count("rom"))
    for (std::size_t i = 0; i < s.gravities.size(); ++i)
      if (s.gravities[i] < 0.1)
        throw InputError(fmt::format("{}: key 'gravities[{}]': {} m/s^2 is below the ROMs' 0.1 m/s^2 (stage 'rom')",
                                     path, i, s.gravities[i]));
  if (asked.count("rom") && s.vehicles.empty())
    throw InputError(fmt::format("{}: key 'stages': 'rom' needs the list 'vehicles'", path));
  for (const auto& st : kCampaignStages)
    if (asked.count(st)) s.stages.push_back(st);
  for (const auto& soil : s.soils)
    if (!soil.crm.empty() && !read_json_file(soil.crm, "CRM soil").is_object())
      throw InputError(fmt::format("{}: soil '{}': {} is not a JSON object (a CRM material)", path, soil.name, soil.crm));
  if (j.contains("options")) {
    if (!j["options"].is_object()) throw InputError(fmt::format("{}: key 'options': expected an object", path));
    for (const auto& [st, o] : j["options"].items()) {
      if (!kStageCommand.count(st))
        throw InputError(fmt::format("{}: key 'options.{}': expected bevameter, calibrate, wheel (both wheel stages), "
                                     "wheel_reference (the reference's wheel only), wheel_table or rom",
                                     path, st));
      if (!o.is_object()) throw InputError(fmt::format("{}: key 'options.{}': expected an object", path, st));
      check_stage_options(path, st, o);
      s.options[st] = o;
    }
    if (s.options.count("wheel") && s.options.count("wheel_reference"))
      for (const auto& [k, v] : s.options["wheel_reference"].items())
        if (s.options["wheel"].contains(k))
          throw InputError(fmt::format("{}: key 'options.wheel_reference.{}': already given in options.wheel, which "
                                       "serves both wheel stages",
                                       path, k));
  }
  if (std::count(s.stages.begin(), s.stages.end(), "wheel_table") &&
      !(s.options.count("wheel_table") && s.options["wheel_table"].contains("loads")))
    throw InputError(fmt::format("{}: key 'options.wheel_table.loads': the wheel_table stage needs the wheel loads "
                                 "[N] to tabulate (those the vehicles put on their wheels)",
                                 path));
  return s;
}

namespace {

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void add_options(const CampaignSpec& s, const std::string& stage, std::vector<std::string>& args) {
  const auto it = s.options.find(stage);
  if (it == s.options.end()) return;
  for (auto& w : command_option_words(kStageCommand.at(stage), it->second)) args.push_back(std::move(w));
}

// The key: the stage, its arguments, the bytes of every file they name and of the files it writes
// (outputs of other jobs by those jobs' keys instead) and the program version, through two FNV-1a
// streams.
std::string job_key(const CampaignJob& job, const std::vector<CampaignJob>& jobs, const std::vector<std::string>& files) {
  Fnv1a64 a, b;
  b.add("terracal campaign job");
  auto add = [&](const std::string& t) {
    a.add(t);
    a.add("\n", 1);
    b.add(t);
    b.add("\n", 1);
  };
  add(TERRACAL_VERSION);
  add(job.stage);
  for (const auto& x : job.args) add(x);
  for (const auto& f : files) add(file_bytes(f));
  for (const auto& [rel, content] : job.writes) add(rel + "\n" + content);
  for (int n : job.needs) add(jobs[n].key);
  return a.hex() + b.hex();
}

std::string gravity_label(double g) { return fmt::format("g{}", g); }

}  // namespace

int add_job(std::vector<CampaignJob>& jobs, CampaignJob j, const std::vector<std::string>& files) {
  j.key = job_key(j, jobs, files);
  j.dir = fmt::format("jobs/{}/{}-{}", j.stage, j.label, j.key.substr(0, 8));
  jobs.push_back(std::move(j));
  return static_cast<int>(jobs.size()) - 1;
}

std::vector<CampaignJob> campaign_jobs(const CampaignSpec& s) {
  std::vector<CampaignJob> jobs;
  auto has = [&](const std::string& st) { return std::count(s.stages.begin(), s.stages.end(), st) > 0; };
  auto push = [&](CampaignJob j, const std::vector<std::string>& files) { return add_job(jobs, std::move(j), files); };
  // Placeholders for other jobs' outputs: replaced by their folders when a job runs.
  int group = 0;
  for (const auto& soil : s.soils)
    for (double g : s.gravities) {
      const std::string base = soil.name + "_" + gravity_label(g);
      const std::string gz = fmt::format("{}", -g);
      const bool shear = s.options.count("bevameter") && s.options.at("bevameter").contains("shear-loads");
      int bev = -1, cal = -1;
      // A CRM material carries its gravity: the entry's copy has the entry's, written into the
      // campaign folder before the job runs (and hashed as the job's input).
      std::pair<std::string, std::string> crm_soil;
      if (!soil.crm.empty()) {
        nlohmann::json m = read_json_file(soil.crm, "CRM soil");
        m["gravity"] = {0.0, 0.0, -g};
        crm_soil = {fmt::format("soils/{}.json", base), m.dump(2) + "\n"};
      }
      const std::string crm_path = "@out/" + crm_soil.first;
      if (has("bevameter")) {
        CampaignJob j{"", "bevameter", base, "", "bevameter", {}, {}, group, {}, {}};
        j.args = soil.scm.empty() ? std::vector<std::string>{"--solver", "crm", "--soil", crm_path}
                                  : std::vector<std::string>{"--solver", "scm", "--scm", soil.scm, "--gravity", "0", "0", gz};
        if (!soil.crm.empty()) j.writes = {crm_soil};
        j.args.insert(j.args.end(), {"--test", shear ? "all" : "plate"});
        add_options(s, "bevameter", j.args);
        bev = push(j, {soil.scm.empty() ? soil.crm : soil.scm});  // the copy's bytes follow from the file and g
      }
      if (has("calibrate")) {
        CampaignJob j{"", "calibrate", base, "", "calibrate", {"--plate", "@0/plate.csv"}, {bev}, group, {}, {}};
        if (shear) j.args.insert(j.args.end(), {"--shear", "@0/shear.csv"});
        add_options(s, "calibrate", j.args);
        cal = push(j, {});
      }
      std::map<std::string, int> table;  // wheel name -> its wheel_table job
      for (const auto& w : s.wheels) {
        const std::string label = base + "_" + w.name;
        if (has("wheel")) {
          CampaignJob j{"", "wheel", label, "", "wheel",
                        {"--terrain", "scm", "--scm", "@0/scm_params.json", "--wheel", w.file, "--gravity", "0", "0", gz},
                        {cal}, group, {}, {}};
          add_options(s, "wheel", j.args);
          push(j, {w.file});
        }
        if (has("wheel_reference")) {
          CampaignJob j{"", "wheel_reference", label, "", "wheel", {}, {}, group, {}, {}};
          j.args = soil.scm.empty()
                       ? std::vector<std::string>{"--terrain", "crm", "--soil", crm_path, "--wheel", w.file}
                       : std::vector<std::string>{"--terrain", "scm", "--scm", soil.scm, "--wheel", w.file, "--gravity", "0", "0", gz};
          if (!soil.crm.empty()) j.writes = {crm_soil};
          add_options(s, "wheel", j.args);
          add_options(s, "wheel_reference", j.args);
          push(j, {w.file, soil.scm.empty() ? soil.crm : soil.scm});
        }
        const bool driven = s.vehicles.empty() || std::any_of(s.vehicles.begin(), s.vehicles.end(),
                                                                [&](const CampaignVehicle& v) { return v.wheel == w.name; });
        if (has("wheel_table") && driven) {
          CampaignJob j{"", "wheel_table", label, "", "wheel-table",
                        {"--scm", "@0/scm_params.json", "--wheel", w.file, "--gravity", "0", "0", gz},
                        {cal}, group, {}, {}};
          j.out_file = "table.h5";
          add_options(s, "wheel_table", j.args);
          table[w.name] = push(j, {w.file});
        }
      }
      for (const auto& v : s.vehicles) {
        if (!has("rom")) break;
        CampaignJob j{"", "rom", base + "_" + v.name, "", "rom",
                      {"--vehicle", v.vehicle, "--maneuver", v.maneuver, "--terrain-table", "@0/table.h5",
                       "--gravity", fmt::format("{}", g)},
                      {table.at(v.wheel)}, group, {}, {}};
        if (!(s.options.count("rom") && s.options.at("rom").contains("model")))
          j.args.insert(j.args.end(), {"--model", "18dof"});
        add_options(s, "rom", j.args);
        std::vector<std::string> files{v.maneuver};
        if (fs::path(v.vehicle).extension() == ".json") files.push_back(v.vehicle);
        push(j, files);
      }
      ++group;
    }
  return jobs;
}

std::vector<std::string> job_command_line(const CampaignJob& job, const std::string& out_dir) {
  std::vector<std::string> a{job.command};
  for (const auto& x : job.args) a.push_back(x);
  a.push_back("--out");
  a.push_back(job.out_file.empty() ? out_dir : out_dir + "/" + job.out_file);
  return a;
}

}  // namespace terracal::app
