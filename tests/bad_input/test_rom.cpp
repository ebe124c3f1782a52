// Bad input to `terracal rom`: the vehicle file (ours and LFDM's), the tire file, the driver file,
// the manoeuvre and the options. Every case exits 2 naming the file, the line or key, the value and
// what was expected, and writes nothing.
#include "bad_input_suite.hpp"

using terracal::test::BadInput;
using terracal::test::InputFile;

namespace {

const std::string kRun = "rom --model 18dof --vehicle hmmwv --inputs {dir}/drive.txt --out {out} ";

// A vehicle file in our format with one line replaced: `key` -> `text`.
std::string vehicle_with(const std::string& key, const std::string& text) {
  std::string v = R"({"type": "ROM vehicle", "name": "test", "effects": ["tire_relaxation", "roll"],
 "mass": 2000, "unsprung_mass": [100, 100], "cg_to_front": 1.5, "cg_to_rear": 1.7, "cg_height": 0.6,
 "yaw_inertia": 4000, "roll_inertia": 1200, "track": 1.8, "roll_center_height": [0.3, 0.3],
 "roll_stiffness": [30000, 30000], "roll_damping": [3000, 3000], "max_steer": 0.6,
 "powertrain": {"crank_inertia": 1, "max_torque_rpm": [[0, 300], [3000, 400]],
   "capacity_factor": [[0, 15], [1, 35]], "torque_ratio": [[0, 2], [1, 1]],
   "gear_ratios": [0.05, 0.1], "upshift_rpm": 2500, "downshift_rpm": 1200, "max_brake_torque": 3000},
 "tire": "tire.json"})";
  const std::string quoted = "\"" + key + "\": ";
  const auto at = v.find(quoted);
  if (at == std::string::npos) return v;
  auto end = at + quoted.size();
  int depth = 0;
  for (; end < v.size(); ++end) {
    const char c = v[end];
    if (c == '[' || c == '{') ++depth;
    if (c == ']' || c == '}') --depth;
    if (depth < 0 || (depth == 0 && c == ',')) break;
  }
  return v.substr(0, at) + text + v.substr(end);
}

const char* kTire = R"({"jw": 6.5, "rr": 0.015, "r0": 0.4699, "pn": 8562.8266, "pnmax": 29969.893, "cx": 185004.42,
 "cy": 164448.37, "kt": 411121.0, "dx": 3700, "dy": 3488, "rdyncoPn": 0.375, "rdyncoP2n": 0.75,
 "dfx0Pn": 151447.2, "dfx0P2n": 236412.79, "fxmPn": 7575.3614, "fxmP2n": 12808.276, "fxsPn": 4657.9208,
 "fxsP2n": 8625.3352, "sxmPn": 0.12, "sxmP2n": 0.15, "sxsPn": 0.9, "sxsP2n": 0.95, "dfy0Pn": 50931.693,
 "dfy0P2n": 94293.84, "fymPn": 6615.0404, "fymP2n": 12509.947, "fysPn": 6091.5092, "fysP2n": 11443.875,
 "symPn": 0.38786, "symP2n": 0.38786, "sysPn": 0.82534, "sysP2n": 0.91309})";

std::vector<InputFile> common_files() {
  return {{"drive.txt", "0 0 0.5 0\n1 0.1 0.5 0\n2 0 0.5 0\n"}, {"tire.json", kTire}};
}

BadInput vehicle(const std::string& name, const std::string& json, std::vector<std::string> phrases) {
  return {name,
          {{"veh.json", json}},
          "rom --model 18dof --vehicle {dir}/veh.json --inputs {dir}/drive.txt --out {out}",
          std::move(phrases)};
}
BadInput driver(const std::string& name, const std::string& text, std::vector<std::string> phrases) {
  return {name,
          {{"bad.txt", text}},
          "rom --model 11dof --vehicle hmmwv --inputs {dir}/bad.txt --out {out}",
          std::move(phrases)};
}
BadInput option(const std::string& args, std::vector<std::string> phrases) {
  return {args, {}, kRun + args, std::move(phrases)};
}

}  // namespace

TEST_CASE("bad input, rom: the vehicle file", "[cli][bad_input][rom]") {
  const std::vector<BadInput> cases = {
      vehicle("unknown key", vehicle_with("mass", "\"mass\": 2000, \"masss\": 1"), {"veh.json", "masss", "unknown"}),
      vehicle("missing key", vehicle_with("yaw_inertia", "\"x\": 1").replace(0, 0, ""), {"veh.json", "yaw_inertia"}),
      vehicle("negative mass", vehicle_with("mass", "\"mass\": -5"), {"veh.json", "'mass'", "-5", "(0, 10000000]"}),
      vehicle("torque map not increasing in speed",
              vehicle_with("max_torque_rpm", "\"max_torque_rpm\": [[0, 300], [3000, 400], [2000, 350]]"),
              {"veh.json", "max_torque_rpm", "row 3", "2000", "increase"}),
      vehicle("torque ratio rising", vehicle_with("torque_ratio", "\"torque_ratio\": [[0, 1], [1, 2]]"),
              {"veh.json", "torque_ratio", "row 2", "must not grow"}),
      vehicle("gear ratios not increasing", vehicle_with("gear_ratios", "\"gear_ratios\": [0.1, 0.05]"),
              {"veh.json", "gear_ratios", "0.05"}),
      vehicle("downshift above upshift", vehicle_with("downshift_rpm", "\"downshift_rpm\": 2600"),
              {"veh.json", "downshift speed 2600 rpm", "upshift speed 2500 rpm"}),
      vehicle("unknown effect", vehicle_with("effects", "\"effects\": [\"tire_relaxaton\"]"),
              {"veh.json", "effects", "tire_relaxaton"}),
      vehicle("suspension on an 18-DOF model",
              vehicle_with("effects", "\"effects\": [\"suspension\"], \"spring_rate\": 1e5"), {"suspension", "24-DOF"}),
      vehicle("tire file missing", vehicle_with("tire", "\"tire\": \"none.json\""), {"none.json"}),
      vehicle("text for a number", vehicle_with("cg_height", "\"cg_height\": \"high\""),
              {"veh.json", "cg_height", "high", "not a number"}),
      vehicle("LFDM vehicle without a tire", R"({"a": 1.6, "b": 1.6, "m": 2000})", {"veh.json", "--tire"}),
      {"preset that does not exist",
       {},
       "rom --model 18dof --vehicle humvee --inputs {dir}/drive.txt --out {out}",
       {"humvee"}},
  };
  terracal::test::check_bad_inputs("bad_rom_vehicle", cases, common_files());
}

TEST_CASE("bad input, rom: the tire file", "[cli][bad_input][rom]") {
  std::string neg = kTire;
  neg.replace(neg.find("\"jw\": 6.5"), 9, "\"jw\": -6.5");
  std::string slips = kTire;
  slips.replace(slips.find("\"sxsPn\": 0.9"), 12, "\"sxsPn\": 0.1");
  const std::vector<BadInput> cases = {
      {"negative wheel inertia", {{"t.json", neg}}, kRun + "--tire {dir}/t.json", {"t.json", "jw", "-6.5"}},
      {"sliding slip below the peak slip", {{"t.json", slips}}, kRun + "--tire {dir}/t.json", {"t.json", "0.1"}},
  };
  terracal::test::check_bad_inputs("bad_rom_tire", cases, common_files());
}

TEST_CASE("bad input, rom: the driver file", "[cli][bad_input][rom]") {
  const std::vector<BadInput> cases = {
      driver("time decreasing", "0 0 0 0\n2 0 0.5 0\n1 0 0.5 0\n", {"bad.txt:3", "time", "1"}),
      driver("text in a number", "0 0 0 0\n1 left 0.5 0\n", {"bad.txt:2", "steering", "left"}),
      driver("throttle above 1", "0 0 1.5 0\n", {"bad.txt:1", "throttle", "1.5", "[0, 1]"}),
      driver("three columns", "0 0 0\n", {"bad.txt:1"}),
      driver("empty file", "", {"bad.txt"}),
  };
  terracal::test::check_bad_inputs("bad_rom_driver", cases, common_files());
}

TEST_CASE("bad input, rom: the manoeuvre and the options", "[cli][bad_input][rom]") {
  const std::vector<BadInput> cases = {
      {"unknown manoeuvre type",
       {{"m.json", R"({"type": "slalom"})"}},
       "rom --model 18dof --vehicle hmmwv --maneuver {dir}/m.json --out {out}",
       {"m.json", "type", "slalom"}},
      {"both --inputs and --maneuver",
       {{"m.json", R"({"type": "straight_acceleration"})"}},
       kRun + "--maneuver {dir}/m.json",
       {"--inputs", "--maneuver"}},
      {"no driver", {}, "rom --model 18dof --vehicle hmmwv --out {out}", {"--inputs", "--maneuver"}},
      {"unknown model",
       {},
       "rom --model 30dof --vehicle hmmwv --inputs {dir}/drive.txt --out {out}",
       {"--model", "30dof"}},
      {"24-DOF model without suspension parameters",
       {{"veh.json", vehicle_with("max_steer", "\"max_steer\": 0.6")}},
       "rom --model 24dof --vehicle {dir}/veh.json --inputs {dir}/drive.txt --out {out}",
       {"24-DOF", "spring_rate", "pitch_inertia"}},
      option("--step 0", {"--step"}),
      option("--integrator rk4", {"--integrator", "rk4"}),
      option("--step 0.05", {"--step 0.05", "--output-rate"}),
      option("--friction 0", {"--friction"}),
      option("--end-time -1", {"--end-time"}),
      option("--vary {dir}/drive.txt", {"--vary", "--batch"}),
      option("--batch 10 --channels vx,speed", {"--channels", "speed"}),
      option("--batch 10 --channels vx,vx", {"--channels", "twice"}),
      option("--batch 10 --integrator cvodes", {"--integrator cvodes", "half-implicit"}),
      option("--batch 0", {"--batch"}),
      option("--batch 10000000 --channels x,y,yaw,vx,vy,yaw_rate,ax,ay,roll --output-rate 1000 --end-time 100",
             {"--batch 10000000", "memory", "--output-rate"}),
      option("--inputs {dir}/drive.txt", {"--inputs", "2 driver files", "--batch"}),
      {"a batch with a manoeuvre",
       {{"m.json", R"({"type": "straight_acceleration"})"}},
       "rom --model 18dof --vehicle hmmwv --maneuver {dir}/m.json --batch 10 --out {out}",
       {"--maneuver", "driver files"}},
      {"vary: unknown parameter",
       {{"v.json", R"({"weight": {"distribution": "normal", "mean": 1, "sd": 1}})"}},
       kRun + "--batch 10 --vary {dir}/v.json",
       {"v.json", "weight"}},
      {"vary: a draw below zero mass",
       {{"v.json", R"({"mass": {"distribution": "normal", "mean": 100, "sd": 1000}})"}},
       kRun + "--batch 1000 --vary {dir}/v.json",
       {"v.json", "mass"}},
  };
  terracal::test::check_bad_inputs("bad_rom_options", cases, common_files());
}
