// Bad input to `terracal vehicle`: the vehicle file, the driver and the options. Every case exits 2
// naming the file or option, the key, the value and what was expected, and writes nothing.
#include "bad_input_suite.hpp"
#include "highfi/vehicle/full_vehicle.hpp"

using terracal::test::BadInput;
using terracal::test::InputFile;

namespace {
const std::string kRun = "vehicle --vehicle hmmwv --inputs {dir}/drive.txt --out {out} ";

std::vector<InputFile> common_files() {
  return {{"drive.txt", "0 0 0 0\n1 0 0.2 0\n"},
          {"sand.json",
           R"({"Type": "SCM", "Soil parameters": {"Bekker Kphi": 1528430, "Bekker Kc": 990, "Bekker n exponent": 1.1,
               "Mohr cohesive limit": 1040, "Mohr friction limit": 28, "Janosi shear coefficient": 0.025,
               "Elastic stiffness": 4e7, "Damping": 3e4}})"}};
}

// The HMMWV preset with one value replaced.
std::string hmmwv_with(const std::function<void(nlohmann::json&)>& edit) {
  nlohmann::json j = nlohmann::json::parse(terracal::vehicle::full_vehicle_preset_json("hmmwv"));
  edit(j);
  return j.dump();
}
}  // namespace

TEST_CASE("bad input, vehicle: the vehicle file, the driver and the options", "[cli][bad_input][vehicle]") {
  const std::string veh = "vehicle --vehicle {dir}/v.json --inputs {dir}/drive.txt --out {out}";
  const std::vector<BadInput> cases = {
      {"negative chassis mass",
       {{"v.json", hmmwv_with([](nlohmann::json& j) { j["chassis"]["mass"] = -10; })}},
       veh,
       {"v.json", "chassis.mass", "-10"}},
      {"a hinge's two points at one place",
       {{"v.json", hmmwv_with([](nlohmann::json& j) {
           j["axles"][0]["suspension"]["upper_arm"]["chassis_back"] =
               j["axles"][0]["suspension"]["upper_arm"]["chassis_front"];
         })}},
       veh,
       {"v.json", "axles[0].suspension.upper_arm.chassis_back"}},
      {"steered axle without steering",
       {{"v.json", hmmwv_with([](nlohmann::json& j) { j.erase("steering"); })}},
       veh,
       {"v.json", "axles", "steered"}},
      {"unknown key", {{"v.json", hmmwv_with([](nlohmann::json& j) { j["whee1"] = 1; })}}, veh, {"v.json", "whee1"}},
      {"not JSON", {{"v.json", "{\"chassis\": "}}, veh, {"v.json", "JSON"}},
      {"no such vehicle", {}, "vehicle --vehicle humvee --inputs {dir}/drive.txt --out {out}", {"humvee"}},
      {"driver file throttle above 1",
       {{"bad.txt", "0 0 1.5 0\n"}},
       "vehicle --vehicle hmmwv --inputs {dir}/bad.txt --out {out}",
       {"bad.txt:1", "throttle", "1.5"}},
      {"no driver", {}, "vehicle --vehicle hmmwv --out {out}", {"--inputs", "--maneuver"}},
      {"SCM terrain without a soil", {}, kRun + "--terrain scm", {"--terrain scm", "--scm FILE"}},
      {"a soil without SCM terrain", {}, kRun + "--scm {dir}/sand.json", {"--scm", "only with --terrain scm"}},
      {"SCM grid out of range", {}, kRun + "--terrain scm --scm {dir}/sand.json --scm-grid 5", {"--scm-grid", "5"}},
      {"SCM step out of range", {}, kRun + "--terrain scm --scm {dir}/sand.json --scm-step 1", {"--scm-step", "1"}},
      {"unknown SCM effect",
       {},
       kRun + "--terrain scm --scm {dir}/sand.json --scm-effects mud",
       {"--scm-effects", "mud"}},
      {"friction on SCM", {}, kRun + "--terrain scm --scm {dir}/sand.json --mu 0.5", {"--mu", "--terrain rigid"}},
      {"SCM set with a negative Kphi",
       {{"bad_sand.json",
         R"({"Type": "SCM", "Soil parameters": {"Bekker Kphi": -5, "Bekker Kc": 990, "Bekker n exponent": 1.1,
             "Mohr cohesive limit": 1040, "Mohr friction limit": 28, "Janosi shear coefficient": 0.025,
             "Elastic stiffness": 4e7, "Damping": 3e4}})"}},
       kRun + "--terrain scm --scm {dir}/bad_sand.json",
       {"bad_sand.json", "Kphi", "-5"}},
      {"no wheel width on SCM",
       {{"v.json", hmmwv_with([](nlohmann::json& j) { j["wheel"].erase("width"); })}},
       veh + " --terrain scm --scm {dir}/sand.json",
       {"wheel.width", "SCM"}},
      {"negative wheel width",
       {{"v.json", hmmwv_with([](nlohmann::json& j) { j["wheel"]["width"] = -1; })}},
       veh,
       {"v.json", "wheel.width", "-1"}},
      {"unknown terrain", {}, kRun + "--terrain mud", {"--terrain", "mud"}},
      {"friction out of range", {}, kRun + "--mu 5", {"--mu", "5"}},
      {"tolerance out of range", {}, kRun + "--rtol 0.5", {"--rtol", "0.5"}},
      {"snapshot rate zero", {}, kRun + "--vtu --vtu-rate 0", {"--vtu-rate", "value 0", "(0, 1000] Hz"}},
      {"snapshot rate too high", {}, kRun + "--vtu --vtu-rate 5000", {"--vtu-rate", "5000", "(0, 1000] Hz"}},
      {"snapshot rate without snapshots", {}, kRun + "--vtu-rate 10", {"--vtu-rate", "only with --vtu"}},
  };
  terracal::test::check_bad_inputs("bad_vehicle", cases, common_files());
}
