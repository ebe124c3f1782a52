// Bad campaign specs: exit 2 naming the key, nothing started (no campaign folder).
#include "bad_input_suite.hpp"

using terracal::test::BadInput;
using terracal::test::InputFile;

namespace {

const std::string kWheel = R"({"radius": 0.47, "width": 0.25, "mass": 108, "angular_velocity": 1.0})";

// A spec file of the JSON fragment `body`, {demo} and {soil} in it expanded as in the arguments.
BadInput spec(const std::string& what, const std::string& body, std::vector<std::string> phrases) {
  return {what, {{"spec.json", terracal::test::expand("{" + body + "}", "")}}, "campaign {dir}/spec.json --out {out}",
          std::move(phrases)};
}

const std::string kSoils = R"("soils": [{"name": "sand", "scm": "{demo}/truth.json"}])";
const std::string kWheels = R"("wheels": [{"name": "w", "wheel": "wheel.json"}])";

std::string ok_but(const std::string& extra) { return kSoils + R"(, "gravities": [9.81], )" + kWheels + extra; }

}  // namespace

TEST_CASE("bad input, campaign: specs", "[cli][bad_input][campaign]") {
  std::vector<BadInput> cases = {
      spec("unknown top-level key", ok_but(R"(, "gravity": 3)"), {"unknown key 'gravity'"}),
      spec("empty soils", R"("soils": [], "gravities": [9.81], )" + kWheels, {"key 'soils': expected a non-empty list"}),
      spec("empty gravities", kSoils + R"(, "gravities": [], )" + kWheels, {"key 'gravities'"}),
      spec("no wheels", kSoils + R"(, "gravities": [9.81])", {"key 'wheels'"}),
      spec("a missing soil file", R"("soils": [{"name": "sand", "scm": "nowhere.json"}], "gravities": [9.81], )" + kWheels,
           {"key 'soils[0].scm'", "nowhere.json", "not found"}),
      spec("duplicate soil names",
           R"("soils": [{"name": "sand", "scm": "{demo}/truth.json"}, {"name": "sand", "scm": "{demo}/truth.json"}], "gravities": [9.81], )" +
               kWheels,
           {"key 'soils[1].name'", "'sand' appears twice"}),
      spec("a soil with both scm and crm",
           R"("soils": [{"name": "s", "scm": "{demo}/truth.json", "crm": "{soil}"}], "gravities": [9.81], )" + kWheels,
           {"key 'soils[0]'", "exactly one of 'scm'"}),
      spec("a gravity out of range", kSoils + R"(, "gravities": [0], )" + kWheels, {"key 'gravities[0]'", "[0.01, 30]"}),
      spec("a duplicate gravity", kSoils + R"(, "gravities": [9.81, 9.81], )" + kWheels, {"key 'gravities[1]'", "twice"}),
      spec("a name that cannot name a folder", R"("soils": [{"name": "a/b", "scm": "{demo}/truth.json"}], "gravities": [9.81], )" + kWheels,
           {"key 'soils[0].name'", "letters, digits"}),
      spec("an unknown stage", ok_but(R"(, "stages": ["bevameter", "plot"])"), {"key 'stages'", "unknown stage", "plot"}),
      spec("calibrate without bevameter", ok_but(R"(, "stages": ["calibrate"])"), {"'calibrate' needs 'bevameter'"}),
      spec("an option the command does not take", ok_but(R"(, "options": {"wheel": {"slipz": [0.1]}})"),
           {"key 'options.wheel.slipz'", "has no option --slipz"}),
      spec("an option value the command refuses", ok_but(R"(, "options": {"wheel": {"duration": -1}})"),
           {"key 'options.wheel.duration'", "refused by terracal wheel --duration"}),
      spec("an option the campaign sets", ok_but(R"(, "options": {"wheel": {"gravity": [0, 0, -1]}})"),
           {"key 'options.wheel.gravity'", "sets --gravity itself"}),
      spec("a wheel option given twice", ok_but(R"(, "options": {"wheel": {"duration": 1}, "wheel_reference": {"duration": 2}})"),
           {"key 'options.wheel_reference.duration'", "already given in options.wheel"}),
      spec("a flag given a number", ok_but(R"(, "options": {"calibrate": {"no-plots": 1}})"),
           {"key 'options.calibrate.no-plots'", "is a flag"}),
      spec("a CRM soil that is no JSON object",
           R"("soils": [{"name": "c", "crm": "wheel_list.json"}], "gravities": [3.71], )" + kWheels,
           {"soil 'c'", "is not a JSON object"}),
      spec("a vehicle on a wheel the spec lacks",
           ok_but(R"(, "vehicles": [{"name": "v", "vehicle": "hmmwv", "maneuver": "wheel.json", "wheel": "tire"}])"),
           {"key 'vehicles[0].wheel'", "is none of the spec's wheels"}),
      spec("a vehicle without its manoeuvre", ok_but(R"(, "vehicles": [{"name": "v", "vehicle": "hmmwv", "wheel": "w"}])"),
           {"key 'vehicles[0].maneuver'"}),
      spec("a vehicle with an unknown key",
           ok_but(R"(, "vehicles": [{"name": "v", "vehicle": "hmmwv", "maneuver": "wheel.json", "wheel": "w", "dof": 18}])"),
           {"unknown key 'vehicles[0].dof'"}),
      spec("the rom stage without vehicles", ok_but(R"(, "stages": ["bevameter", "calibrate", "wheel_table", "rom"],
           "options": {"wheel_table": {"loads": [3000]}})"),
           {"key 'stages'", "'rom' needs the list 'vehicles'"}),
      spec("a wheel table without its loads",
           ok_but(R"(, "vehicles": [{"name": "v", "vehicle": "hmmwv", "maneuver": "wheel.json", "wheel": "w"}])"),
           {"key 'options.wheel_table.loads'", "needs the wheel loads"}),
      spec("a ROM option the rom command refuses",
           ok_but(R"(, "vehicles": [{"name": "v", "vehicle": "hmmwv", "maneuver": "wheel.json", "wheel": "w"}],
           "options": {"wheel_table": {"loads": [3000]}, "rom": {"model": "30dof"}})"),
           {"key 'options.rom.model'", "30dof"}),
      spec("a gravity below the ROMs'",
           R"("soils": [{"name": "sand", "scm": "{demo}/truth.json"}], "gravities": [0.05], )" + kWheels +
               R"(, "vehicles": [{"name": "v", "vehicle": "hmmwv", "maneuver": "wheel.json", "wheel": "w"}],
           "options": {"wheel_table": {"loads": [3000]}})",
           {"key 'gravities[0]'", "below the ROMs' 0.1 m/s^2"}),
      {"--shard out of range", {}, "campaign {demo}/truth.json --out {out} --shard 2/2", {"--shard 2/2", "0 <= i < N"}},
      {"--status of a folder that holds no campaign", {}, "campaign --status {dir}", {"no campaign.sqlite"}},
  };
  terracal::test::check_bad_inputs("bad_campaign", cases, {{"wheel.json", kWheel}, {"wheel_list.json", "[1, 2]"}});
}
