// The rig commands (bevameter, wheel) write the curve files of docs/formats.md (their bad input:
// tests/bad_input/).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "bayes/observations.hpp"
#include "core/csv.hpp"
#include "tests/apps/cli_runner.hpp"
#include "tests/scratch_dir.hpp"

using namespace terracal;
using namespace terracal::test;

namespace {
const char* kSand =
    R"({"Type": "SCM", "Soil parameters": {"Bekker Kphi": 1528430, "Bekker Kc": 990, "Bekker n exponent": 1.1,
        "Mohr cohesive limit": 1040, "Mohr friction limit": 28, "Janosi shear coefficient": 0.025}})";
const char* kWheel = R"({"radius": 0.47, "width": 0.25, "mass": 108, "angular_velocity": 1.0})";
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
  // run.json: the runs' own walls (a study's cost) and the sweep's elapsed time (settling included),
  // which for one slip run alone is at least the run's own.
  const nlohmann::json run = nlohmann::json::parse(std::ifstream(d + "/scm/run.json"));
  CHECK(run.at("wall_seconds").get<double>() > 0);
  CHECK(run.at("elapsed_seconds").get<double>() >= run.at("wall_seconds").get<double>());
}
