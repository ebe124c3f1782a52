// `terracal rom` end to end: a manoeuvre and a driver file write trajectory.csv with the contract's
// header, 100 Hz rows, and run.json; with a driver file, inputs.txt holding its rows.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <catch2/catch.hpp>

#include "core/csv.hpp"

#include "core/device_selftest.hpp"
#include "core/vehicle/driver_inputs.hpp"
#include "rom/trajectory_csv.hpp"
#include "tests/apps/cli_runner.hpp"
#include "tests/skip.hpp"

using namespace terracal::test;

TEST_CASE("terracal rom: a step steer writes trajectory.csv at 100 Hz", "[cli][rom]") {
  const ScratchDir dir("cli_rom");
  std::ofstream(dir.str() + "/m.json") << R"({"type": "step_steer", "steering": 0.1, "step_time": 1,
    "initial_speed": 15, "end_time": 3})";
  const CliResult r = run_cli(
      "rom --model 18dof --vehicle hmmwv --maneuver " + dir.str() + "/m.json --out " + dir.str() + "/out --no-plots",
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
  // inputs.txt holds the manoeuvre's held inputs as steps: driven by it, the same run again.
  const CliResult again =
      run_cli("rom --model 18dof --vehicle hmmwv --inputs " + dir.str() +
                  "/out/inputs.txt --initial-speed 15 --end-time 3 --out " + dir.str() + "/again --no-plots",
              dir.str());
  REQUIRE(again.exit_code == 0);
  const terracal::CsvTable a = terracal::CsvTable::read(dir.str() + "/out/trajectory.csv");
  const terracal::CsvTable b = terracal::CsvTable::read(dir.str() + "/again/trajectory.csv");
  REQUIRE(a.rows() == b.rows());
  for (const char* c : {"x", "y", "yaw", "vx", "yaw_rate"})
    CHECK(b.number(b.rows() - 1, c) == Approx(a.number(a.rows() - 1, c)).margin(1e-4));
}

TEST_CASE("terracal rom --inputs: inputs.txt gives back the driver file's rows", "[cli][rom]") {
  const ScratchDir dir("cli_rom_inputs");
  // Commas, a comment and values without an exact double (inputs.txt keeps every digit).
  std::ofstream(dir.str() + "/drive.txt") << "# a gentle turn\n0 0 0.3 0\n0.4, 0.1, 0.35, 0\n1 -0.05 0.2 0.1\n";
  const CliResult r = run_cli("rom --model 11dof --vehicle hmmwv --inputs " + dir.str() +
                                  "/drive.txt --initial-speed 10 --no-plots --out " + dir.str() + "/out",
                              dir.str());
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const terracal::DriverSeries given = terracal::DriverSeries::read(dir.str() + "/drive.txt");
  const terracal::DriverSeries applied = terracal::DriverSeries::read(dir.str() + "/out/inputs.txt");
  CHECK(applied.times() == given.times());
  CHECK(applied.steering() == given.steering());
  CHECK(applied.throttle() == given.throttle());
  CHECK(applied.braking() == given.braking());
}

#include <hdf5.h>

namespace {
std::vector<hsize_t> dataset_dims(hid_t file, const char* name) {
  const hid_t d = H5Dopen2(file, name, H5P_DEFAULT);
  if (d < 0) return {};
  const hid_t s = H5Dget_space(d);
  std::vector<hsize_t> dims(H5Sget_simple_extent_ndims(s));
  H5Sget_simple_extent_dims(s, dims.data(), nullptr);
  H5Sclose(s);
  H5Dclose(d);
  return dims;
}
}  // namespace

TEST_CASE("terracal rom --batch: varied vehicles write batch.h5 with their parameters, metrics and channels",
          "[cli][rom][batch]") {
  const ScratchDir dir("cli_rom_batch");
  std::ofstream(dir.str() + "/drive.txt") << "0 0 0.3 0\n1 0.2 0.5 0\n2 0 0.5 0\n";
  std::ofstream(dir.str() + "/vary.json")
      << R"({"mass": {"distribution": "normal", "mean": 2100, "sd": 50}, "friction": {"distribution": "uniform", "low": 0.5, "high": 1}})";
  const CliResult r = run_cli("rom --model 11dof --vehicle hmmwv --inputs " + dir.str() +
                                  "/drive.txt --initial-speed 10 "
                                  "--batch 64 --vary " +
                                  dir.str() +
                                  "/vary.json --seed 3 --device cpu --channels vx,ay "
                                  "--output-rate 50 --out " +
                                  dir.str() + "/out",
                              dir.str());
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const hid_t f = H5Fopen((dir.str() + "/out/batch.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(f >= 0);
  CHECK(dataset_dims(f, "/parameters/mass") == std::vector<hsize_t>{64});
  CHECK(dataset_dims(f, "/summary/final_vx") == std::vector<hsize_t>{64});
  CHECK(dataset_dims(f, "/channels/ay") == std::vector<hsize_t>{64, 101});
  CHECK(dataset_dims(f, "/time") == std::vector<hsize_t>{101});
  H5Fclose(f);
}

TEST_CASE("terracal rom --batch --device cuda without a CUDA device: exit 2, nothing written", "[cli][rom][batch]") {
  if (terracal::cuda_device_info().available) {
    terracal::test::report_skip("rom --device cuda refusal", "a CUDA device is present here");
    return;
  }
  const ScratchDir dir("cli_rom_nocuda");
  std::ofstream(dir.str() + "/drive.txt") << "0 0 0.3 0\n1 0 0.3 0\n";
  const CliResult r = run_cli("rom --model 18dof --vehicle hmmwv --inputs " + dir.str() +
                                  "/drive.txt --batch 10 --device cuda --out " + dir.str() + "/out",
                              dir.str());
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("--device cuda: no CUDA device available") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(dir.str() + "/out"));
}

TEST_CASE("terracal rom --batch with several driver files: vehicle i follows file i mod their number",
          "[cli][rom][batch]") {
  const ScratchDir dir("cli_rom_drivers");
  std::ofstream(dir.str() + "/left.txt") << "0 0.2 0.3 0\n2 0.2 0.3 0\n";
  std::ofstream(dir.str() + "/right.txt") << "0 -0.2 0.3 0\n2 -0.2 0.3 0\n";
  const CliResult r = run_cli("rom --model 11dof --vehicle hmmwv --inputs " + dir.str() + "/left.txt " + dir.str() +
                                  "/right.txt --initial-speed 10 --batch 4 --device cpu --out " + dir.str() + "/out",
                              dir.str());
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const hid_t f = H5Fopen((dir.str() + "/out/batch.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(f >= 0);
  const hid_t d = H5Dopen2(f, "/summary/final_yaw", H5P_DEFAULT);
  double yaw[4] = {};
  H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, yaw);
  H5Dclose(d);
  H5Fclose(f);
  CHECK(yaw[0] > 0.1);   // left
  CHECK(yaw[1] < -0.1);  // right
  CHECK(yaw[2] == yaw[0]);
  CHECK(yaw[3] == yaw[1]);
}
