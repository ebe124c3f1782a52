// Bad input to `terracal vehicle`: the vehicle file, the driver and the options. Every case exits 2
// naming the file or option, the key, the value and what was expected, and writes nothing.
#include "bad_input_suite.hpp"
#include "highfi/vehicle/full_vehicle.hpp"

using terracal::test::BadInput;
using terracal::test::InputFile;

namespace {
const std::string kRun = "vehicle --vehicle hmmwv --inputs {dir}/drive.txt --out {out} ";

std::vector<InputFile> common_files() { return {{"drive.txt", "0 0 0 0\n1 0 0.2 0\n"}}; }

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
      {"SCM terrain not yet", {}, kRun + "--terrain scm", {"--terrain scm", "rigid"}},
      {"unknown terrain", {}, kRun + "--terrain mud", {"--terrain", "mud"}},
      {"friction out of range", {}, kRun + "--mu 5", {"--mu", "5"}},
      {"tolerance out of range", {}, kRun + "--rtol 0.5", {"--rtol", "0.5"}},
      {"snapshot rate zero", {}, kRun + "--vtu --vtu-rate 0", {"--vtu-rate", "value 0", "(0, 1000] Hz"}},
      {"snapshot rate too high", {}, kRun + "--vtu --vtu-rate 5000", {"--vtu-rate", "5000", "(0, 1000] Hz"}},
      {"snapshot rate without snapshots", {}, kRun + "--vtu-rate 10", {"--vtu-rate", "only with --vtu"}},
  };
  terracal::test::check_bad_inputs("bad_vehicle", cases, common_files());
}
