// `terracal rom` end to end: a manoeuvre and a driver file write trajectory.csv with the contract's
// header, 100 Hz rows, and run.json.
#include <fstream>
#include <sstream>
#include <string>

#include <catch2/catch.hpp>

#include "rom/trajectory_csv.hpp"
#include "tests/apps/cli_runner.hpp"

using namespace terracal::test;

TEST_CASE("terracal rom: a step steer writes trajectory.csv at 100 Hz", "[cli][rom]") {
  const ScratchDir dir("cli_rom");
  std::ofstream(dir.str() + "/m.json") << R"({"type": "step_steer", "steering": 0.1, "step_time": 1,
    "initial_speed": 15, "end_time": 3})";
  const CliResult r = run_cli("rom --model 18dof --vehicle hmmwv --maneuver " + dir.str() + "/m.json --out " +
                                  dir.str() + "/out --no-plots",
                              dir.str());
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  std::ifstream f(dir.str() + "/out/trajectory.csv");
  std::string header, line;
  std::getline(f, header);
  CHECK(header == terracal::rom::kTrajectoryHeader);
  int rows = 0;
  double yaw_rate_end = 0;
  while (std::getline(f, line)) {
    ++rows;
    std::stringstream s(line);
    std::string cell;
    for (int c = 0; c <= 9 && std::getline(s, cell, ','); ++c)
      if (c == 9) yaw_rate_end = std::stod(cell);
  }
  CHECK(rows == 301);
  CHECK(yaw_rate_end > 0.05);  // positive steering turns left
  CHECK(std::ifstream(dir.str() + "/out/run.json").good());
}
