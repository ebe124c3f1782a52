// The rig commands (bevameter, wheel, pipeline) write the curve files of docs/formats.md, and bad
// input exits 2 naming the option or key, before any output is written.
#include <catch2/catch.hpp>

#include <filesystem>

#include "bayes/observations.hpp"
#include "core/csv.hpp"
#include "tests/apps/cli_runner.hpp"
#include "tests/scratch_dir.hpp"

using namespace terracal;
using namespace terracal::test;
using Catch::Matchers::Contains;

namespace {
const char* kSand =
    R"({"Type": "SCM", "Soil parameters": {"Bekker Kphi": 1528430, "Bekker Kc": 990, "Bekker n exponent": 1.1,
        "Mohr cohesive limit": 1040, "Mohr friction limit": 28, "Janosi shear coefficient": 0.025}})";
const char* kWheel = R"({"radius": 0.47, "width": 0.25, "mass": 108, "angular_velocity": 1.0})";
const char* kCrmSoil =
    R"({"density": 1700, "young_modulus": 1e6, "poisson_ratio": 0.3, "mu_s": 0.7, "mu_2": 0.7, "I0": 0.03,
  "grain_diameter": 0.005, "cohesion": 0, "gravity": [0, 0, -9.81]})";
}  // namespace

TEST_CASE("terracal bevameter and wheel on SCM and Wong-Reece write the curve files", "[apps][rigs]") {
  ScratchDir dir("cli_rigs");
  const std::string d = dir.str();
  write(d + "/sand.json", kSand);
  write(d + "/wheel.json", kWheel);
  CliResult r = run_cli("bevameter --solver scm --scm " + d +
                            "/sand.json --test all --plates 0.1,0.2 --max-sinkage 0.05 "
                            "--shear-loads 200,400 --shear-angle 0.3 --shear-settle 0.3 --grid 0.01 --no-plots --out " +
                            d + "/bev",
                        d);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  // The calibrator reads them back: two plates with an unload-reload cycle, two loads.
  const auto plate = bayes::load_plate_csv(d + "/bev/plate.csv");
  CHECK(plate.radii.size() == 2);
  const auto shear = bayes::load_shear_csv(d + "/bev/shear.csv");
  CHECK(shear.points.size() > 20);
  r = run_cli("wheel --terrain wong-reece --scm " + d + "/sand.json --wheel " + d +
                  "/wheel.json --slips 0.1,0.3 --no-plots --out " + d + "/wr",
              d);
  REQUIRE(r.exit_code == 0);
  const CsvTable wr = CsvTable::read(d + "/wr/wheel.csv");
  CHECK(wr.rows() == 2);
  CHECK(wr.number(1, "slip") == 0.3);
  r = run_cli("wheel --terrain scm --scm " + d + "/sand.json --wheel " + d +
                  "/wheel.json --slips 0.3 --duration 1 --no-plots --out " + d + "/scm",
              d);
  REQUIRE(r.exit_code == 0);
  const CsvTable scm = CsvTable::read(d + "/scm/wheel.csv");
  CHECK(scm.number(0, "dbp_N") > 0);
  CHECK(std::filesystem::exists(d + "/scm/wheel_series.csv"));
}

TEST_CASE("rig commands: bad input exits 2 naming the option or key, and writes nothing", "[apps][rigs]") {
  ScratchDir dir("cli_rigs_bad");
  const std::string d = dir.str();
  write(d + "/sand.json", kSand);
  write(d + "/soil.json", kCrmSoil);
  write(d + "/wheel.json", kWheel);
  write(d + "/wheel_typo.json", R"({"radius": 0.47, "widht": 0.25, "mass": 108})");
  write(d + "/wheel_neg.json", R"({"radius": -0.47, "width": 0.25, "mass": 108})");
  write(d + "/sand_bad.json", R"({"Soil parameters": {"Bekker Kphi": 1e6, "Bekker Kc": 0, "Bekker n exponent": 9,
        "Mohr cohesive limit": 0, "Mohr friction limit": 30, "Janosi shear coefficient": 0.01}})");
  write(d + "/soil_bad.json",
        R"({"density": -5, "young_modulus": 1e6, "poisson_ratio": 0.3, "mu_s": 0.7, "mu_2": 0.7, "I0": 0.03,
        "grain_diameter": 0.005, "cohesion": 0, "gravity": [0, 0, -9.81]})");
  struct Case {
    std::string args;
    std::vector<std::string> expect;
  };
  const std::string out = " --out " + d + "/out";
  const std::vector<Case> cases = {
      {"bevameter --solver fem --scm " + d + "/sand.json --shear-loads 100" + out, {"--solver", "fem"}},
      {"bevameter --solver scm --soil " + d + "/soil.json --shear-loads 100" + out, {"--scm"}},
      {"bevameter --solver scm --scm " + d + "/sand.json --test plate --plates 0.2,abc" + out, {"--plates", "abc"}},
      {"bevameter --solver scm --scm " + d + "/sand.json --test shear" + out, {"--shear-loads"}},
      {"bevameter --solver scm --scm " + d + "/sand.json --test cone --shear-loads 100" + out, {"--test", "cone"}},
      {"bevameter --solver scm --scm " + d + "/sand_bad.json --test plate" + out, {"Bekker n exponent", "9"}},
      {"bevameter --solver scm --scm " + d + "/sand.json --test plate --grid -1" + out, {"grid", "-1"}},
      {"bevameter --solver scm --scm " + d + "/sand.json --test plate --scm-effects mud" + out,
       {"--scm-effects", "mud"}},
      {"bevameter --solver crm --soil " + d + "/soil_bad.json --test plate --device cpu" + out, {"density", "-5"}},
      {"bevameter --solver crm --soil " + d + "/soil.json --test plate --device cpu --bin-depth-scale 0.5" + out,
       {"--bin-depth-scale", "0.5"}},
      {"bevameter --solver crm --soil " + d + "/soil.json --test plate --device cpu --plate-wall-radii 1" + out,
       {"--plate-wall-radii", "1"}},
      {"bevameter --solver crm --soil " + d + "/soil.json --test plate --device cpu --settle-jitter 0.5" + out,
       {"--settle-jitter", "0.5"}},
      {"bevameter --solver crm --soil " + d + "/soil.json --test plate --device cpu --hourglass-damping 3" + out,
       {"--hourglass-damping", "3"}},
      {"bevameter --solver crm --soil " + d + "/soil.json --test plate --device cpu --h-over-d0 2" + out,
       {"--h-over-d0", "2"}},
      {"wheel --terrain crm --soil " + d + "/soil.json --wheel " + d + "/wheel.json --device cpu --h-over-d0 0.9" + out,
       {"--h-over-d0", "0.9"}},
      {"wheel --terrain crm --soil " + d + "/soil.json --wheel " + d +
           "/wheel.json --device cpu --marker-velocity slip" + out,
       {"--marker-velocity", "slip"}},
      {"wheel --terrain scm --scm " + d + "/sand.json --wheel " + d + "/wheel_typo.json" + out, {"width", "missing"}},
      {"wheel --terrain scm --scm " + d + "/sand.json --wheel " + d + "/wheel_neg.json" + out, {"radius", "-0.47"}},
      {"wheel --terrain scm --scm " + d + "/sand.json --wheel " + d + "/wheel.json --slips 0.2,1.5" + out,
       {"slip", "1.5"}},
      {"wheel --terrain dem --scm " + d + "/sand.json --wheel " + d + "/wheel.json" + out, {"--terrain", "dem"}},
      {"wheel --terrain crm --scm " + d + "/sand.json --wheel " + d + "/wheel.json" + out, {"--soil"}},
      {"wheel --terrain scm --scm " + d + "/sand.json --wheel " + d + "/wheel.json --duration 0" + out,
       {"duration", "0"}},
      {"pipeline --soil " + d + "/soil_bad.json" + out, {"density", "-5"}},
      {"pipeline --soil " + d + "/soil.json --shear-loads 490,-3" + out, {"--shear-loads", "-3"}},
      {"pipeline --soil " + d + "/soil.json --annulus 0.15" + out, {"--annulus"}},
      {"pipeline --soil " + d + "/soil.json --checks=annulus,plates" + out, {"--checks", "plates"}},
      {"pipeline --soil " + d + "/soil.json --device cpu --hourglass-damping -1" + out, {"--hourglass-damping", "-1"}},
      {"bevameter --solver crm --soil " + d + "/soil.json --test plate --device cpu --hourglass-stiffness 0.5" + out,
       {"--hourglass-stiffness", "0.5"}},
      {"pipeline --soil " + d + "/soil.json --device cpu --h-over-d0 1.7" + out, {"--h-over-d0", "1.7"}},
      {"pipeline --soil " + d + "/soil.json --device cpu --marker-velocity adami" + out,
       {"--marker-velocity", "adami"}},
      {"pipeline --soil " + d + "/soil.json --device cpu --plate-depth-scale 0.1" + out,
       {"--plate-depth-scale", "0.1"}},
      {"pipeline --soil " + d + "/soil.json --device cpu --checks --check-realisations 0" + out,
       {"--check-realisations", "0"}},
      {"bevameter --solver crm --soil " + d + "/soil.json --test plate --device cpu --settle-seed -4" + out,
       {"--settle-seed", "-4"}},
      {"bevameter --solver scm --scm " + d + "/sand.json --test shear --shear-loads 500 --shear-load-ramp 1.5" + out,
       {"--shear-load-ramp", "1.5"}},
  };
  for (const auto& c : cases) {
    const CliResult r = run_cli(c.args, d);
    INFO(c.args << "\nstderr: " << r.err);
    CHECK(r.exit_code == 2);
    for (const auto& e : c.expect) CHECK_THAT(r.err, Contains(e));
    CHECK_FALSE(std::filesystem::exists(d + "/out/plate.csv"));
    CHECK_FALSE(std::filesystem::exists(d + "/out/wheel.csv"));
  }
}
