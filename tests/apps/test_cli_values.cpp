// Issue 23: no input silently dropped or bent. Every bad value of every command, and every --out that
// cannot be written, exits 2 with a message naming the option (or file and key), the value and what
// was expected, before any work: no output folder is left behind. One row per case.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/out_dir.hpp"
#include "core/errors.hpp"
#include "tests/apps/cli_runner.hpp"
#include "tests/scratch_dir.hpp"

using namespace terracal;
using namespace terracal::test;
namespace fs = std::filesystem;

namespace {

struct ValueCase {
  const char* name;
  // {dir}: the scratch folder; {out}: {dir}/made/out (neither may exist afterwards); {truth}, {plate},
  // {shear}: the demo data set; {soil}: a CRM soil; other files are written into {dir} below.
  std::string args;
  int code;
  std::vector<std::string> phrases;  // each must appear in stderr
};

std::string replaced(std::string s, const std::string& key, const std::string& value) {
  for (std::size_t at = s.find(key); at != std::string::npos; at = s.find(key, at + value.size()))
    s.replace(at, key.size(), value);
  return s;
}

nlohmann::json demo_truth() { return nlohmann::json::parse(read_file(demo_data("truth.json"))); }
nlohmann::json crm_soil() {
  return nlohmann::json::parse(
      read_file(std::string(TERRACAL_SOURCE_DIR) + "/studies/pipeline/bevameter_soil_2022.json"));
}

// The input files the rows name, in `d`.
void write_inputs(const std::string& d) {
  write(d + "/wheel.json", R"({"radius": 0.47, "width": 0.25, "mass": 108, "angular_velocity": 1.0})");
  write(d + "/wheel_still.json", R"({"radius": 0.47, "width": 0.25, "mass": 108, "angular_velocity": 0})");
  write(d + "/wheel_massless.json", R"({"radius": 0.47, "width": 0.25, "mass": 0})");
  write(d + "/afile", "not a folder\n");
  for (const auto& [file, key, value] :
       {std::tuple{"k0", "Janosi shear coefficient", 0.0}, std::tuple{"phi95", "Mohr friction limit", 95.0},
        std::tuple{"n0", "Bekker n exponent", 0.0}, std::tuple{"typo", "Bekker Kx", 1.0}}) {
    nlohmann::json j = demo_truth();
    j["Soil parameters"][key] = value;
    write(d + "/scm_" + file + ".json", j.dump());
  }
  for (const auto& [file, g] :
       {std::pair{"up", std::vector<double>{0, 0, 9.81}}, std::pair{"none", std::vector<double>{0, 0, 0}}}) {
    nlohmann::json j = crm_soil();
    j["gravity"] = g;
    write(d + "/soil_" + file + ".json", j.dump());
  }
  nlohmann::json body = {{"name", "box"},
                         {"shape", {{"type", "box"}, {"size", {0.05, 0.05, 0.05}}}},
                         {"position", {0.15, 0.15, 0.2}},
                         {"motion", {{"type", "dynamic"}}},
                         {"mass", 1},
                         {"inertia", {1e-3, -1e-3, 1e-3}}};
  nlohmann::json scene = {{"soil", crm_soil()},
                          {"bin", {{"size", {0.3, 0.3, 0.2}}, {"fill_height", 0.12}}},
                          {"resolution", {{"spacing", 1e-4}}},
                          {"duration", 0.1}};
  write(d + "/scene_fine.json", scene.dump());
  scene["resolution"]["spacing"] = 0.01;
  write(d + "/scene_ok.json", scene.dump());
  scene["bodies"] = {body};
  write(d + "/scene_inertia.json", scene.dump());
}

const std::string kTruth = " --truth {truth}";
const std::string kCal = "calibrate --plate {plate} --out {out}";
const std::string kBev = "bevameter --solver crm --soil {soil} --device cpu --test plate --out {out}";
const std::string kBevScm = "bevameter --solver scm --scm {truth} --out {out}";
const std::string kWheelScm = "wheel --terrain scm --scm {truth} --wheel {dir}/wheel.json --out {out}";
const std::string kPipe = "pipeline --soil {soil} --device cpu --out {out}";

const std::vector<ValueCase> kCases = {
    // Seeds: every --seed takes [0, 2^64 - 1] and nothing else (CLI11 wrapped -1 to 2^64 - 1).
    {"negative seed",
     "synthesize" + kTruth + " --out {out} --seed -1",
     2,
     {"--seed: value -1 is outside [0, 18446744073709551615]"}},
    {"seed beyond 2^64",
     "synthesize" + kTruth + " --out {out} --seed 18446744073709551616",
     2,
     {"--seed: value 18446744073709551616 is outside"}},
    {"fractional seed", kCal + " --seed 1.5", 2, {"--seed: value 1.5 is not a whole number"}},
    {"hex seed", "demo --calibration-only --out {out} --seed 0x10", 2, {"--seed: value 0x10 is not a whole number"}},
    {"pipeline seed", kPipe + " --seed -5", 2, {"--seed: value -5 is outside"}},
    {"settle seed", kBev + " --settle-seed -1", 2, {"--settle-seed: value -1 is outside [0, 4611686018427387904]"}},
    // Whole numbers: "1e3", "3.5" and values beyond the type name the option, the value and the range.
    {"chains 1e3", kCal + " --chains 1e3", 2, {"--chains: value 1e3 is not a whole number"}},
    {"chains 3.5", kCal + " --chains 3.5", 2, {"--chains: value 3.5 is not a whole number"}},
    {"chains beyond the range", kCal + " --chains 300", 2, {"--chains 300: expected 4 to 256 chains"}},
    {"max draws beyond long",
     kCal + " --max-draws 99999999999999999999",
     2,
     {"--max-draws: value 99999999999999999999 is outside"}},
    {"max draws too many", kCal + " --max-draws 1000000000", 2, {"--max-draws 1000000000: expected 10 to 100000000"}},
    {"min ess negative", kCal + " --min-ess -1", 2, {"--min-ess: value -1 is outside (0, 1000000000]"}},
    {"plate points 1e3",
     "synthesize" + kTruth + " --out {out} --plate-points 1e3",
     2,
     {"--plate-points: value 1e3 is not a whole number in [1, 100000]"}},
    {"shear points 0",
     "synthesize" + kTruth + " --out {out} --shear-points 0",
     2,
     {"--shear-points: value 0 is outside [1, 100000]"}},
    {"record every -5",
     "crm --scene {dir}/scene_fine.json --out {out} --record-every -5",
     2,
     {"--record-every: value -5 is outside [1, 1099511627776]"}},
    {"check realisations 17",
     kPipe + " --check-realisations 17",
     2,
     {"--check-realisations: value 17 is outside [1, 16]"}},
    // Real numbers that were replaced by a default or passed unchecked.
    {"negative step", kBevScm + " --test plate --step -0.01", 2, {"--step: value -0.01 is outside [0, 0.1] s"}},
    {"negative shear step",
     kBevScm + " --test shear --shear-loads 100 --shear-step -0.01",
     2,
     {"--shear-step: value -0.01 is outside [0, 0.1] s"}},
    {"plate speed 0",
     kBevScm + " --test plate --plate-speed 0",
     2,
     {"--plate-speed: value 0 is outside [0.0001, 10] m/s"}},
    {"shear angle negative",
     kBevScm + " --test shear --shear-loads 100 --shear-angle -1",
     2,
     {"--shear-angle: value -1 is outside"}},
    {"shear rate huge", kBevScm + " --test shear --shear-loads 100 --shear-rate 1e9", 2, {"--shear-rate: value 1e9"}},
    {"negative plate radius", kBevScm + " --test plate --plates 0.2,-0.3", 2, {"--plates: value -0.3 in the list"}},
    {"annulus inside out",
     kBevScm + " --test shear --shear-loads 100 --annulus 0.2,0.15",
     2,
     {"--annulus 0.2,0.15: expected the inner radius below the outer one"}},
    {"sinkage beyond 5 radii",
     kBevScm + " --test plate --plates 0.1 --max-sinkage 0.6",
     2,
     {"--max-sinkage 0.6 m: more than 5 radii of the plate r = 0.1 m"}},
    {"plate spacing negative", kBev + " --plate-spacing -0.01", 2, {"--plate-spacing: value -0.01 is outside"}},
    {"slip beyond 1", kWheelScm + " --slips 0,1.2", 2, {"--slips: value 1.2 in the list '0,1.2' is outside (-1, 1)"}},
    {"slips not numbers", kWheelScm + " --slips 0,,0.2", 2, {"--slips: value '0,,0.2' is not a comma-separated list"}},
    {"duration 0", kWheelScm + " --duration 0", 2, {"--duration: value 0 is outside [0.001, 100000] s"}},
    {"average from 1", kWheelScm + " --average-from 1", 2, {"--average-from: value 1 is outside [0, 0.95]"}},
    {"wheel duration negative", kPipe + " --wheel-duration -1", 2, {"--wheel-duration: value -1 is outside"}},
    {"noise above 0.2",
     "synthesize" + kTruth + " --out {out} --noise 0.3",
     2,
     {"--noise: value 0.3 is outside [0, 0.2]"}},
    {"synthesize negative plate",
     "synthesize" + kTruth + " --out {out} --plates 0.1,-0.2",
     2,
     {"--plates: value -0.2 is outside (0, 10] m"}},
    // synthesize reads --truth as wheel and bevameter read an SCM set.
    {"truth Janosi k 0",
     "synthesize --truth {dir}/scm_k0.json --out {out}",
     2,
     {"scm_k0.json: key 'Soil parameters.Janosi shear coefficient' = 0: expected in [1e-6, 10] m"}},
    {"truth friction 95",
     "synthesize --truth {dir}/scm_phi95.json --out {out}",
     2,
     {"key 'Soil parameters.Mohr friction limit' = 95"}},
    {"truth n 0",
     "synthesize --truth {dir}/scm_n0.json --out {out}",
     2,
     {"key 'Soil parameters.Bekker n exponent' = 0"}},
    {"truth unknown key",
     "synthesize --truth {dir}/scm_typo.json --out {out}",
     2,
     {"unknown key 'Soil parameters.Bekker Kx'"}},
    // Physically meaningless inputs.
    {"gravity up (--gravity)",
     kWheelScm + " --gravity 0 0 9.81",
     2,
     {"--gravity [0, 0, 9.81] m/s^2: expected gravity pointing down"}},
    {"no gravity (--gravity)", kWheelScm + " --gravity 0 0 0", 2, {"--gravity [0, 0, 0] m/s^2: expected gravity"}},
    {"--gravity with CRM", kBev + " --gravity 0 0 -1.62", 2, {"--gravity: only for SCM and Wong-Reece"}},
    {"CRM soil gravity up",
     "bevameter --solver crm --soil {dir}/soil_up.json --test plate --out {out}",
     2,
     {"soil_up.json: key 'soil.gravity': [0, 0, 9.81] m/s^2 does not point down"}},
    {"CRM soil without gravity on a rig",
     "bevameter --solver crm --soil {dir}/soil_none.json --test plate --out {out}",
     2,
     {"warning", "the soil has no weight",
      "soil_none.json: key 'soil.gravity' [0, 0, 0] m/s^2: expected gravity pointing"}},
    {"massless wheel",
     "wheel --terrain scm --scm {truth} --wheel {dir}/wheel_massless.json --out {out}",
     2,
     {"wheel_massless.json: key 'mass': value 0 is outside the allowed range (0, 1000000]"}},
    {"negative inertia",
     "crm --scene {dir}/scene_inertia.json --out {out}",
     2,
     {"key 'bodies[0].inertia': principal moments must not be negative"}},
    {"resume without a checkpoint",
     "crm --scene {dir}/scene_ok.json --resume --out {out}",
     2,
     {"--resume: {dir}/made/out/checkpoint.h5 does not exist"}},
    // --out: an existing file, a path under /proc or under a file: exit 2 naming --out, before any work.
    {"out is a file (synthesize)",
     "synthesize" + kTruth + " --out {dir}/afile",
     2,
     {"--out {dir}/afile: exists and is not a folder"}},
    {"out is a file (calibrate)", "calibrate --plate {plate} --out {dir}/afile", 2, {"--out {dir}/afile: exists"}},
    {"out is a file (demo)", "demo --calibration-only --out {dir}/afile", 2, {"--out {dir}/afile: exists"}},
    {"out is a file (crm)", "crm --scene {dir}/scene_fine.json --out {dir}/afile", 2, {"--out {dir}/afile: exists"}},
    {"out is a file (bevameter)",
     "bevameter --solver scm --scm {truth} --test plate --out {dir}/afile",
     2,
     {"--out {dir}/afile: exists"}},
    {"out is a file (wheel)",
     "wheel --terrain scm --scm {truth} --wheel {dir}/wheel.json --out {dir}/afile",
     2,
     {"--out {dir}/afile: exists"}},
    {"out is a file (pipeline)", "pipeline --soil {soil} --out {dir}/afile", 2, {"--out {dir}/afile: exists"}},
    {"out under /proc",
     "synthesize" + kTruth + " --out /proc/terracal_no_such_folder/out",
     2,
     {"--out /proc/terracal_no_such_folder/out: cannot make the folder"}},
    {"out under a file",
     "synthesize" + kTruth + " --out {dir}/afile/out",
     2,
     {"--out {dir}/afile/out:", "is not a folder"}},
    {"out empty", "synthesize" + kTruth + " --out ''", 2, {"--out '': an empty path"}},
    // Memory: a resolution that cannot fit is refused, naming the option, the estimate and what is available.
    {"CRM scene far too fine",
     "crm --scene {dir}/scene_fine.json --out {out}",
     2,
     {"scene_fine.json: key 'resolution.spacing' 0.0001 m: a CRM bin", "GiB of memory where", "is available",
      "expected a coarser resolution.spacing"}},
    {"bevameter spacing far too fine",
     kBev + " --spacing 0.0005",
     2,
     {"--spacing 0.0005 m: a CRM bin", "needs about", "expected a coarser --spacing"}},
    {"plate spacing far too fine", kBev + " --plate-spacing 0.0005", 2, {"--plate-spacing 0.0005 m: a CRM bin"}},
    {"wheel spacing far too fine",
     "wheel --terrain crm --soil {soil} --device cpu --wheel {dir}/wheel.json --spacing 0.001 "
     "--out {out}",
     2,
     {"--spacing 0.001 m: a CRM bin", "for the wheel"}},
    {"pipeline spacing far too fine", kPipe + " --spacing 0.001", 2, {"--spacing 0.001 m: a CRM bin"}},
    {"SCM grid far too fine",
     kBevScm + " --test plate --plates 2 --max-sinkage 0.5 --grid 1e-4",
     2,
     {"--grid 0.0001 m: SCM under the plate r = 2 m", "needs about", "expected a coarser --grid"}},
};

}  // namespace

TEST_CASE("bad values of every command: exit 2 naming option, value and range; no --out left", "[cli][values]") {
  const ScratchDir scratch("values");
  const std::string d = scratch.str();
  write_inputs(d);
  for (const auto& c : kCases) {
    std::string args = c.args;
    for (const auto& [key, value] :
         {std::pair{"{out}", d + "/made/out"}, std::pair{"{dir}", d}, std::pair{"{truth}", demo_data("truth.json")},
          std::pair{"{plate}", demo_data("plate.csv")},
          std::pair{"{soil}", std::string(TERRACAL_SOURCE_DIR) + "/studies/pipeline/bevameter_soil_2022.json"}})
      args = replaced(args, key, value);
    const CliResult r = run_cli(args, d);
    INFO(c.name << "\n" << args << "\nstderr: " << r.err);
    CHECK(r.exit_code == c.code);
    for (const auto& p : c.phrases) CHECK(r.err.find(replaced(p, "{dir}", d)) != std::string::npos);
    CHECK_FALSE(fs::exists(d + "/made"));
  }
}

TEST_CASE("suspicious but legitimate inputs run, with a 'warning' line on stderr", "[cli][values]") {
  const ScratchDir scratch("values_warn");
  const std::string d = scratch.str();
  write_inputs(d);
  const CliResult r = run_cli("wheel --terrain wong-reece --scm " + demo_data("truth.json") + " --wheel " + d +
                                  "/wheel_still.json --slips 0,0.2 --no-plots --out " + d + "/out",
                              d);
  INFO(r.err);
  CHECK(r.exit_code == 0);
  CHECK(r.err.find("warning") != std::string::npos);
  CHECK(r.err.find("angular_velocity is 0: it does not turn") != std::string::npos);
}

TEST_CASE("--out in a folder without write permission: exit 2 naming --out", "[cli][values]") {
  if (::geteuid() == 0) {
    SUCCEED("root writes in any folder: nothing to refuse");
    return;
  }
  const ScratchDir scratch("values_ro");
  const std::string d = scratch.str();
  fs::create_directories(d + "/locked");
  fs::permissions(d + "/locked", fs::perms::owner_read | fs::perms::owner_exec);
  const CliResult r = run_cli("synthesize --truth " + demo_data("truth.json") + " --out " + d + "/locked/out", d);
  fs::permissions(d + "/locked", fs::perms::owner_all);
  INFO(r.err);
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("--out " + d + "/locked/out: cannot make the folder") != std::string::npos);
  CHECK_FALSE(fs::exists(d + "/locked/out"));
}

TEST_CASE("OutDir removes the empty folders a failed run made, and nothing else", "[cli][values]") {
  const ScratchDir scratch("values_outdir");
  const std::string d = scratch.str();
  auto fail_in = [](const std::string& path, bool write_output) {
    try {
      const app::OutDir out = app::prepare_out_dir("--out", path);
      fs::create_directories(path);
      if (write_output) write(path + "/plate.csv", "plate_radius_m,sinkage_m,force_N\n");
      throw InputError("refused after the folder was made");
    } catch (const InputError&) {
    }
  };
  fail_in(d + "/a/b", false);
  CHECK_FALSE(fs::exists(d + "/a"));  // both folders it made, innermost first
  fail_in(d + "/c/d", true);
  CHECK(fs::exists(d + "/c/d/plate.csv"));  // outputs are never removed
  fs::create_directories(d + "/e");
  fail_in(d + "/e", false);
  CHECK(fs::exists(d + "/e"));  // a folder that was there before stays
  {
    const app::OutDir out = app::prepare_out_dir("--out", d + "/f");
    fs::create_directories(d + "/f");
  }
  CHECK(fs::exists(d + "/f"));  // a run that ends normally keeps its folder
  CHECK_THROWS_AS(app::prepare_out_dir("--out", d + "/c/d/plate.csv"), InputError);
}
