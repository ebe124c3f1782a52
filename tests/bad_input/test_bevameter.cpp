// Bad input to `terracal bevameter`: the soil files (--scm, --soil) and the options of both solvers.
// Everything is refused before the first plate runs, so no case spends time simulating.
#include <nlohmann/json.hpp>

#include "bad_input_suite.hpp"
#include "tests/test_paths.hpp"

using terracal::test::BadInput;
using terracal::test::InputFile;

namespace {

const std::string kScm = "bevameter --solver scm --scm {demo}/truth.json --out {out} ";
const std::string kCrm = "bevameter --solver crm --soil {soil} --device cpu --test plate --out {out} ";

// The pipeline study's CRM soil with `key` set to `value`.
InputFile soil_with(const std::string& name, const std::string& key, const nlohmann::json& value) {
  nlohmann::json j = nlohmann::json::parse(
      terracal::test::read_file(terracal::test::source_dir() + "/studies/pipeline/bevameter_soil_2022.json"));
  j[key] = value;
  return {name, j.dump()};
}

std::vector<InputFile> soil_files() {
  return {soil_with("soil_dense.json", "density", -5),
          soil_with("soil_up.json", "gravity", {0, 0, 9.81}),
          soil_with("soil_none.json", "gravity", {0, 0, 0}),
          {"sand_bad.json", R"({"Soil parameters": {"Bekker Kphi": 1e6, "Bekker Kc": 0, "Bekker n exponent": 9,
             "Mohr cohesive limit": 0, "Mohr friction limit": 30, "Janosi shear coefficient": 0.01}})"}};
}

BadInput scm(const std::string& args, std::vector<std::string> phrases) {
  return {args, {}, kScm + args, std::move(phrases)};
}
BadInput crm(const std::string& args, std::vector<std::string> phrases) {
  return {args, {}, kCrm + args, std::move(phrases)};
}

}  // namespace

TEST_CASE("bad input, bevameter: soil files", "[cli][bad_input]") {
  const std::vector<BadInput> cases = {
      {"SCM set with n = 9",
       {},
       "bevameter --solver scm --scm {dir}/sand_bad.json --test plate --out {out}",
       {"Bekker n exponent", "9"}},
      {"CRM soil of negative density",
       {},
       "bevameter --solver crm --soil {dir}/soil_dense.json --device cpu --test plate --out {out}",
       {"density", "-5"}},
      {"CRM soil with gravity pointing up",
       {},
       "bevameter --solver crm --soil {dir}/soil_up.json --test plate --out {out}",
       {"soil_up.json: key 'soil.gravity': [0, 0, 9.81] m/s^2 does not point down"}},
      {"CRM soil without gravity: warned as a scene, refused on a rig",
       {},
       "bevameter --solver crm --soil {dir}/soil_none.json --test plate --out {out}",
       {"warning", "the soil has no weight",
        "soil_none.json: key 'soil.gravity' [0, 0, 0] m/s^2: expected gravity pointing"}},
      {"--soil with the SCM solver",
       {},
       "bevameter --solver scm --soil {soil} --shear-loads 100 --out {out}",
       {"--scm"}},
  };
  terracal::test::check_bad_inputs("bad_bev_soil", cases, soil_files());
}

TEST_CASE("bad input, bevameter: options", "[cli][bad_input]") {
  const std::vector<BadInput> cases = {
      scm("--solver fem", {"--solver", "fem"}),
      scm("--test cone --shear-loads 100", {"--test", "cone"}),
      scm("--test shear", {"--shear-loads"}),
      scm("--test plate --plates 0.2,abc", {"--plates", "abc"}),
      scm("--test plate --plates 0.2,-0.3", {"--plates: value -0.3 in the list"}),
      scm("--test plate --plates 0.1,0.2,0.1", {"--plates 0.1,0.2,0.1: the value 0.1 is given twice"}),
      scm("--test plate --grid -1", {"grid", "-1"}),
      scm("--test plate --scm-effects mud", {"--scm-effects", "mud"}),
      scm("--test plate --step -0.01", {"--step: value -0.01 is outside [0, 0.1] s"}),
      scm("--test shear --shear-loads 100 --shear-step -0.01", {"--shear-step: value -0.01 is outside [0, 0.1] s"}),
      scm("--test plate --plate-speed 0", {"--plate-speed: value 0 is outside [0.0001, 10] m/s"}),
      scm("--test plate --plate-unload-speed -0.01", {"--plate-unload-speed: value -0.01 is outside", "0 (off)"}),
      scm("--test plate --plate-unload-speed 20", {"--plate-unload-speed: value 20 is outside"}),
      scm("--test shear --shear-loads 100 --shear-angle -1", {"--shear-angle: value -1 is outside"}),
      scm("--test shear --shear-loads 100 --shear-rate 1e9", {"--shear-rate: value 1e9"}),
      scm("--test shear --shear-loads 500 --shear-load-ramp 1.5", {"--shear-load-ramp", "1.5"}),
      scm("--test shear --shear-loads 100 --annulus 0.2,0.15",
          {"--annulus 0.2,0.15: expected the inner radius below the outer one"}),
      scm("--test plate --plates 0.1 --max-sinkage 0.6",
          {"--max-sinkage 0.6 m: more than 5 radii of the plate r = 0.1 m"}),
      scm("--test plate --gravity 0 0 9.81", {"--gravity [0, 0, 9.81] m/s^2: expected gravity pointing down"}),
      // The other solver's options are refused, not ignored.
      scm("--test plate --spacing 0.005 --settle-time 0.5",
          {"--spacing, --settle-time: for CRM only; --solver/--terrain scm does not read them"}),
      crm("--grid 0.005", {"--grid: for SCM only; --solver/--terrain crm does not read it"}),
      crm("--gravity 0 0 -1.62", {"--gravity: only for SCM and Wong-Reece"}),
      crm("--plate-spacing -0.01", {"--plate-spacing: value -0.01 is outside"}),
      crm("--bin-depth-scale 0.5", {"--bin-depth-scale", "0.5"}),
      crm("--plate-wall-radii 1", {"--plate-wall-radii", "1"}),
      crm("--settle-jitter 0.5", {"--settle-jitter", "0.5"}),
      crm("--settle-seed -1", {"--settle-seed: value -1 is outside [0, 4611686018427387904]"}),
      crm("--hourglass-damping 3", {"--hourglass-damping", "3"}),
      crm("--hourglass-stiffness 0.5", {"--hourglass-stiffness", "0.5"}),
      crm("--h-over-d0 2", {"--h-over-d0", "2"}),
      crm("--concurrent-runs 65", {"--concurrent-runs: value 65 is outside [0, 64]"}),
      crm("--concurrent-runs 2.5", {"--concurrent-runs", "2.5"}),
      {"--out is a file",
       {{"afile", "x\n"}},
       "bevameter --solver scm --scm {demo}/truth.json --test plate --out {dir}/afile",
       {"--out {dir}/afile: exists and is not a folder"}},
  };
  terracal::test::check_bad_inputs("bad_bev_opt", cases);
}

// A resolution that cannot fit in memory is refused before anything is allocated, naming the option,
// the estimate and what is available (it ended in std::bad_alloc, naming nothing).
TEST_CASE("bad input, bevameter: resolutions beyond memory", "[cli][bad_input]") {
  const std::vector<BadInput> cases = {
      crm("--spacing 0.0005", {"--spacing 0.0005 m: a CRM bin", "needs about", "expected a coarser --spacing"}),
      crm("--plate-spacing 0.0005", {"--plate-spacing 0.0005 m: a CRM bin"}),
      scm("--test plate --plates 2 --max-sinkage 0.5 --grid 1e-4",
          {"--grid 0.0001 m: SCM under the plate r = 2 m", "needs about", "expected a coarser --grid"}),
  };
  terracal::test::check_bad_inputs("bad_bev_mem", cases);
}
