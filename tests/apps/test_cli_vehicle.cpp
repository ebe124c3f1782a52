// terracal vehicle: a short run of the full HMMWV writes trajectory.csv with the reduced-order
// vehicles' columns, wheels.csv whose loads carry the vehicle, and run.json; with --vtu, ParaView
// snapshots of its bodies at the snapshot rate, listed in vtu/vehicle.pvd, without changing the run;
// inputs.txt, the driver inputs applied, read back as a driver file (and driving the same run again).
#include <catch2/catch.hpp>

#include <filesystem>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "core/csv.hpp"
#include "core/vehicle/driver_inputs.hpp"
#include "core/vtu_writer.hpp"
#include "highfi/vehicle/full_vehicle.hpp"
#include "highfi/vehicle/vehicle_vtu.hpp"
#include "rom/trajectory_csv.hpp"
#include "tests/apps/cli_runner.hpp"
#include "tests/highfi/vehicle/hmmwv_rack.hpp"
#include "tests/scratch_dir.hpp"
#include "tests/vtu_payload.hpp"

using namespace terracal;
using namespace terracal::test;

TEST_CASE("terracal vehicle: a short run writes the trajectory and the wheel loads", "[apps][vehicle]") {
  ScratchDir dir("cli_vehicle");
  const std::string root = dir.path.string();
  // A throttle ramp; the middle row lies on it (0.15 has no exact double: inputs.txt keeps every digit).
  test::write(root + "/drive.txt", "# time steering throttle braking\n0 0 0 0\n0.25, 0, 0.15, 0\n0.5 0 0.3 0\n");
  const CliResult r =
      run_cli("vehicle --vehicle hmmwv --inputs " + root + "/drive.txt --out " + root + "/o --no-plots", root);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  // inputs.txt, read as a driver file, gives back the rows of the one given.
  const DriverSeries given = DriverSeries::read(root + "/drive.txt");
  const DriverSeries applied = DriverSeries::read(root + "/o/inputs.txt");
  CHECK(applied.times() == given.times());
  CHECK(applied.steering() == given.steering());
  CHECK(applied.throttle() == given.throttle());
  CHECK(applied.braking() == given.braking());
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
  CHECK_FALSE(run.contains("vtu"));
  CHECK_FALSE(std::filesystem::exists(root + "/o/vtu"));  // no snapshots without --vtu
}

namespace {
// The chassis's x (trajectory.csv's second column) in each row.
std::vector<double> chassis_x(const std::string& trajectory_csv) {
  std::istringstream in(test::read_file(trajectory_csv));
  std::string line;
  std::getline(in, line);
  std::vector<double> x;
  while (std::getline(in, line)) x.push_back(std::stod(line.substr(line.find(',') + 1)));
  return x;
}
}  // namespace

TEST_CASE("terracal vehicle --vtu: snapshots of the bodies at the snapshot rate, listed in vehicle.pvd",
          "[apps][vehicle][vtu]") {
  ScratchDir dir("cli_vehicle_vtu");
  const std::string root = dir.path.string();
  test::write(root + "/drive.txt", "0 0 0 0\n0.5 0 0.3 0\n");
  const std::string run = "vehicle --vehicle hmmwv --inputs " + root + "/drive.txt --end-time 0.1 --initial-speed 2 " +
                          "--no-plots --out " + root;
  const CliResult plain = run_cli(run + "/plain", root);
  REQUIRE(plain.exit_code == 0);
  // The default 20 Hz over 0.1 s: snapshots at 0, 0.05 and 0.1 s.
  const CliResult r = run_cli(run + "/o --vtu", root);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto entries = read_pvd(root + "/o/vtu/vehicle.pvd");
  REQUIRE(entries.size() == 3);
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(root + "/o/vtu")) ++files;
  CHECK(files == 4);          // the snapshots and the collection, no temporary left
  std::vector<double> box_x;  // the chassis box's centre along x, per snapshot
  for (std::size_t k = 0; k < entries.size(); ++k) {
    INFO("snapshot " << k);
    CHECK(entries[k].first == Approx(0.05 * double(k)).margin(1e-12));
    CHECK(entries[k].second == fmt::format("vehicle_{:05d}.vtu", k));
    const std::string xml = test::slurp(root + "/o/vtu/" + entries[k].second);
    CHECK(xml.find(fmt::format("        {}\n", entries[k].first)) != std::string::npos);  // TimeValue
    const auto points = test::array_payload<float>(xml, "Points");
    const auto velocity = test::array_payload<float>(xml, "velocity");
    const auto name_id = test::array_payload<float>(xml, "name_id");
    const auto body = test::array_payload<float>(xml, "body");
    const auto types = test::array_payload<std::uint8_t>(xml, "types");
    const auto connectivity = test::array_payload<std::int64_t>(xml, "connectivity");
    const auto offsets = test::array_payload<std::int64_t>(xml, "offsets");
    REQUIRE(points.size() == velocity.size());
    REQUIRE(name_id.size() == types.size());
    REQUIRE(offsets.size() == types.size());
    // One wheel (32 quads and 2 caps) per corner, one chassis box.
    std::set<float> wheels;
    int wheel_cells = 0, boxes = 0;
    for (std::size_t c = 0; c < types.size(); ++c) {
      if (name_id[c] == float(vehicle::VtuPart::wheel)) wheels.insert(body[c]), ++wheel_cells;
      if (name_id[c] != float(vehicle::VtuPart::chassis)) continue;
      ++boxes;
      REQUIRE(types[c] == 12);  // VTK_HEXAHEDRON
      double sum = 0;
      for (std::int64_t i = offsets[c] - 8; i < offsets[c]; ++i) {
        const std::size_t p = std::size_t(connectivity[std::size_t(i)]);
        sum += points[3 * p];
        // Settled at rest, then started at 2 m/s: the chassis moves at 2 m/s forward at first.
        if (k == 0) CHECK(std::abs(velocity[3 * p] - 2) < 1e-3);
      }
      box_x.push_back(sum / 8);
    }
    CHECK(wheels.size() == 4);
    CHECK(wheel_cells == 4 * 34);
    CHECK(boxes == 1);
  }
  // The box moves with the chassis of trajectory.csv (rows at 100 Hz).
  const std::vector<double> x = chassis_x(root + "/o/trajectory.csv");
  REQUIRE(x.size() == 11);
  REQUIRE(box_x.size() == 3);
  CHECK(box_x[1] - box_x[0] == Approx(x[5] - x[0]).margin(2e-3));
  CHECK(box_x[2] - box_x[0] == Approx(x[10] - x[0]).margin(2e-3));
  CHECK(box_x[2] - box_x[0] > 0.15);
  // The run is the same with snapshots as without, and run.json names what the ids index.
  CHECK(test::read_file(root + "/o/trajectory.csv") == test::read_file(root + "/plain/trajectory.csv"));
  CHECK(test::read_file(root + "/o/wheels.csv") == test::read_file(root + "/plain/wheels.csv"));
  const auto j = nlohmann::json::parse(test::read_file(root + "/o/run.json"));
  CHECK(j["vtu"]["snapshots"].get<long>() == 3);
  CHECK(j["vtu"]["rate_hz"].get<double>() == 20);
  CHECK(j["vtu"]["bodies"][0].get<std::string>() == "chassis");
  CHECK(j["vtu"]["names"][1].get<std::string>() == "wheel");
  CHECK_FALSE(std::filesystem::exists(root + "/plain/vtu"));

  // 30 Hz falls between the 100 Hz rows: snapshots at k / 30 s still (the integrator's state
  // interpolated there), and the run unchanged.
  const CliResult r30 = run_cli(run + "/o30 --vtu --vtu-rate 30", root);
  REQUIRE(r30.exit_code == 0);
  const auto e30 = read_pvd(root + "/o30/vtu/vehicle.pvd");
  REQUIRE(e30.size() == 4);
  for (std::size_t k = 0; k < e30.size(); ++k) CHECK(e30[k].first == Approx(double(k) / 30).margin(1e-12));
  CHECK(test::read_file(root + "/o30/trajectory.csv") == test::read_file(root + "/plain/trajectory.csv"));
}

TEST_CASE("terracal vehicle --terrain scm: the wheels sink into the soil and carry the vehicle",
          "[apps][vehicle][scm]") {
  ScratchDir dir("cli_vehicle_scm");
  const std::string root = dir.path.string();
  test::write(root + "/drive.txt", "0 0 0 0\n0.2 0 0 0\n");
  test::write(root + "/sand.json",
              R"({"Type": "SCM", "Soil parameters": {"Bekker Kphi": 1528430, "Bekker Kc": 990, "Bekker n exponent": 1.1,
                  "Mohr cohesive limit": 1040, "Mohr friction limit": 28, "Janosi shear coefficient": 0.025,
                  "Elastic stiffness": 4e7, "Damping": 3e4}})");
  const CliResult r = run_cli("vehicle --vehicle hmmwv --terrain scm --scm " + root + "/sand.json --inputs " + root +
                                  "/drive.txt --out " + root + "/o --no-plots --vtu --vtu-rate 5",
                              root);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto run = nlohmann::json::parse(test::read_file(root + "/o/run.json"));
  CHECK(run["terrain"] == "scm");
  CHECK(run["rtol"].get<double>() == 1e-3);  // the default on SCM
  CHECK(run["scm"]["grid"].get<double>() == 0.02);
  CHECK(run["scm"]["effects"] == nlohmann::json::array({"damping"}));
  // After settling on the sand each wheel has sunk several centimetres and the four carry the weight.
  std::istringstream wheels(test::read_file(root + "/o/wheels.csv"));
  std::string line;
  std::getline(wheels, line);
  double fz = 0;
  for (int k = 0; k < 4 && std::getline(wheels, line); ++k) {
    std::vector<double> v;
    std::stringstream cells(line);
    for (std::string c; std::getline(cells, c, ',');) v.push_back(std::stod(c));
    REQUIRE(v.size() == 9);
    fz += v[2];
    CHECK(v[8] > 0.03);  // sinkage_m
    CHECK(v[8] < 0.15);
    CHECK(v[7] == 0);  // no tire deflection: the wheel is rigid on soil
  }
  const double weight = vehicle::load_full_vehicle("hmmwv").total_mass() * 9.81;
  CHECK(std::abs(fz - weight) / weight < 0.01);
  // With --vtu the soil's surface too: soil.pvd lists a snapshot per vehicle snapshot (0 and 0.2 s);
  // the surface holds the four ruts, its lowest point as deep as the deepest wheel within a node's slope.
  CHECK(std::filesystem::exists(root + "/o/vtu/soil.pvd"));
  CHECK(read_pvd(root + "/o/vtu/soil.pvd").size() == 2);
  const std::string soil = test::read_file(root + "/o/vtu/soil_00001.vtu");
  CHECK(soil.find("NumberOfCells=\"0\"") == std::string::npos);
  const auto points = test::array_payload<float>(soil, "Points");
  const auto plastic = test::array_payload<float>(soil, "plastic_sinkage");
  REQUIRE(points.size() == 3 * plastic.size());
  double lowest = 0, deepest = 0;
  for (std::size_t k = 0; k < plastic.size(); ++k) {
    lowest = std::min(lowest, double(points[3 * k + 2]));
    deepest = std::max(deepest, double(plastic[k]));
  }
  double wheel = 0;
  std::istringstream rows(test::read_file(root + "/o/wheels.csv"));
  std::getline(rows, line);
  while (std::getline(rows, line)) wheel = std::max(wheel, std::stod(line.substr(line.rfind(',') + 1)));
  INFO("surface lowest " << lowest << " m, deepest plastic sinkage " << deepest << " m, deepest wheel " << wheel
                         << " m");
  CHECK(std::abs(lowest + deepest) < 1e-6);  // heights are the undisturbed level less the sinkage
  CHECK(std::abs(deepest - wheel) < 0.01);   // the ruts as deep as the wheels
}

TEST_CASE("terracal vehicle: a vehicle file with rack-and-pinion steering drives a manoeuvre", "[apps][vehicle]") {
  ScratchDir dir("cli_vehicle_rack");
  const std::string root = dir.path.string();
  test::write(root + "/rack.json", test::hmmwv_rack_json().dump(2));
  test::write(root + "/dlc.json", R"({"type": "iso3888_1", "initial_speed": 10, "target_speed": 10})");
  const CliResult r = run_cli("vehicle --vehicle " + root + "/rack.json --maneuver " + root +
                                  "/dlc.json --end-time 2 --no-plots --out " + root + "/o",
                              root);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto run = nlohmann::json::parse(test::read_file(root + "/o/run.json"));
  CHECK(run["max_constraint_violation"].get<double>() < 1e-5);
  // The lane change starts with a turn to the left: by 2 s the chassis has moved left of its start.
  std::istringstream traj(test::read_file(root + "/o/trajectory.csv"));
  std::string line, last;
  while (std::getline(traj, line)) last = line;
  std::vector<double> v;
  std::stringstream cells(last);
  for (std::string c; std::getline(cells, c, ',');) v.push_back(std::stod(c));
  INFO(last);
  CHECK(v[1] > 15);   // x: at about 10 m/s
  CHECK(v[2] > 0.1);  // y: to the left
  // inputs.txt: the inputs applied, a knot at every control time (0.01 s; each new output is reached
  // linearly within it) from 0 to the end, the first steering to the left.
  const DriverSeries in = DriverSeries::read(root + "/o/inputs.txt");
  REQUIRE(in.size() == 201);
  CHECK(in.start_time() == 0);
  CHECK(in.end_time() == 2);
  double most_left = 0;
  for (int k = 0; k < in.size(); ++k) {
    INFO("row " << k);
    CHECK(in.times()[std::size_t(k)] == Approx(0.01 * k).margin(1e-12));
    CHECK(std::abs(in.steering()[std::size_t(k)]) <= 1);
    most_left = std::max(most_left, in.steering()[std::size_t(k)]);
  }
  CHECK(in.steering()[0] == 0);  // the controller's first output is reached over the first period
  CHECK(most_left > 0.05);
  // Driven by inputs.txt the vehicle drives the same run (the integrator stops at the control times
  // only in the manoeuvre's run: a few micrometres apart after 2 s).
  const CliResult again = run_cli("vehicle --vehicle " + root + "/rack.json --inputs " + root +
                                      "/o/inputs.txt --initial-speed 10 --no-plots --out " + root + "/again",
                                  root);
  INFO(again.err);
  REQUIRE(again.exit_code == 0);
  std::istringstream traj2(test::read_file(root + "/again/trajectory.csv"));
  std::string last2;
  while (std::getline(traj2, line)) last2 = line;
  std::vector<double> v2;
  std::stringstream cells2(last2);
  for (std::string c; std::getline(cells2, c, ',');) v2.push_back(std::stod(c));
  REQUIRE(v2.size() == v.size());
  CHECK(v2[0] == v[0]);                  // time: 2 s, the file's last row
  CHECK(std::abs(v2[1] - v[1]) < 1e-4);  // x
  CHECK(std::abs(v2[2] - v[2]) < 1e-4);  // y
  CHECK(std::abs(v2[4] - v[4]) < 1e-5);  // yaw
  CHECK(std::abs(v2[7] - v[7]) < 1e-4);  // vx
}
