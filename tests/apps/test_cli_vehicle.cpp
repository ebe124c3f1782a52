// terracal vehicle: a short run of the full HMMWV writes trajectory.csv with the reduced-order
// vehicles' columns, wheels.csv whose loads carry the vehicle, and run.json.
#include <catch2/catch.hpp>

#include <sstream>

#include <nlohmann/json.hpp>

#include "core/csv.hpp"
#include "highfi/vehicle/full_vehicle.hpp"
#include "rom/trajectory_csv.hpp"
#include "tests/apps/cli_runner.hpp"
#include "tests/scratch_dir.hpp"

using namespace terracal;
using namespace terracal::test;

TEST_CASE("terracal vehicle: a short run writes the trajectory and the wheel loads", "[apps][vehicle]") {
  ScratchDir dir("cli_vehicle");
  const std::string root = dir.path.string();
  test::write(root + "/drive.txt", "0 0 0 0\n0.5 0 0.3 0\n");
  const CliResult r =
      run_cli("vehicle --vehicle hmmwv --inputs " + root + "/drive.txt --out " + root + "/o --no-plots", root);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  std::istringstream traj(test::read_file(root + "/o/trajectory.csv"));
  std::string header, line;
  std::getline(traj, header);
  CHECK(header == rom::kTrajectoryHeader);
  int rows = 0;
  while (std::getline(traj, line)) ++rows;
  CHECK(rows == 51);  // 0 to 0.5 s at 100 Hz
  // At time 0 (settled, at rest) the four tires carry the vehicle's weight.
  std::istringstream wheels(test::read_file(root + "/o/wheels.csv"));
  std::getline(wheels, header);
  CHECK(header == "time,wheel,fz_N,fx_N,fy_N,slip_x,slip_y,deflection_m,sinkage_m");
  double fz = 0;
  for (int k = 0; k < 4 && std::getline(wheels, line); ++k)
    fz += std::stod(line.substr(line.find(',', line.find(',') + 1) + 1));
  const double weight = vehicle::load_full_vehicle("hmmwv").total_mass() * 9.81;
  CHECK(std::abs(fz - weight) / weight < 1e-3);
  const auto run = nlohmann::json::parse(test::read_file(root + "/o/run.json"));
  CHECK(run["max_constraint_violation"].get<double>() < 1e-6);
  CHECK(run["steps"].get<long>() > 0);
}
