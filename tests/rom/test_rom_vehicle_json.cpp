// Vehicle files: LFDM's HMMWV vehicle and tire files load to the same vehicle as our preset (whose
// numbers came from them), maps converted from rpm to rad/s.
#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/vehicle/tmeasy_params.hpp"
#include "rom/batch_vary.hpp"
#include "rom/rom_vehicle_edit.hpp"
#include "rom/rom_vehicle_json.hpp"

using namespace terracal;
using namespace terracal::rom;

namespace {
// LFDM's wheeled_vehicle_models/18dof/data/json/HMMWV.json (the published data file).
const char* kLfdmHmmwv = R"({"a": 1.6889, "b": 1.6889, "m": 2097.85, "h": 0.713, "jz": 4519, "jx": 1289, "jxz": 3.265,
 "cf": 1.82, "cr": 1.82, "muf": 139.133, "mur": 139.133, "hrcf": 0.379, "hrcr": 0.327, "krof": 31000, "kror": 31000,
 "brof": 3300, "bror": 3300, "nonLinearSteer": false, "maxSteer": 0.6525249, "crankInertia": 1.093,
 "upshiftRPM": 2500, "downshiftRPM": 1200, "gearRatios": [0.04, 0.08, 0.16],
 "torqueMap": [[-100, 258.0], [800, 328.52], [900, 421.4], [1000, 497.94], [1100, 559.0], [1200, 607.16],
   [1300, 641.56], [1400, 665.64], [1500, 678.54], [1600, 681.98], [1700, 677.68], [1800, 665.64], [1900, 648.44],
   [2000, 626.08], [2100, 599.42], [2200, 571.04], [2300, 540.08], [2400, 509.98], [2500, 479.88], [2700, -344.0]],
 "lossesMap": [[-50, 30], [0, 0], [50, -30], [1000, -50], [2000, -70], [3000, -90]], "tcBool": true,
 "capacityFactorMap": [[0.00, 15.00], [0.25, 15.00], [0.50, 15.00], [0.75, 16.00], [0.90, 18.00], [1.00, 35.00]],
 "torqueRatioMap": [[0.00, 2.00], [0.25, 1.80], [0.50, 1.50], [0.75, 1.15], [1.00, 1.00]],
 "maxBrakeTorque": 4000, "c1": 0, "c0": 0, "step": 0.001, "throttleMod": false})";
}  // namespace

TEST_CASE("rom vehicle files: LFDM's HMMWV files load as our preset", "[rom]") {
  const RomVehicle preset = load_rom_vehicle("hmmwv");
  const TmeasyParams tire = read_tmeasy(tmeasy_json(preset.tire[0]), "tire");
  const RomVehicle lfdm = read_rom_vehicle(nlohmann::json::parse(kLfdmHmmwv), "HMMWV.json", ".", &tire);
  CHECK(lfdm.mass == preset.mass);
  CHECK(lfdm.cg_height == preset.cg_height);
  CHECK(lfdm.roll_stiffness[1] == preset.roll_stiffness[1]);
  CHECK(lfdm.powertrain.gears == 3);
  CHECK(lfdm.powertrain.upshift_speed[2] == Approx(2500 * M_PI / 30));
  CHECK(lfdm.powertrain.max_torque(1600 * M_PI / 30) == Approx(681.98));
  CHECK(lfdm.has(kEffectTorqueConverter));
  CHECK(lfdm.has(kEffectTireRelaxation));
  for (double rpm : {500.0, 1234.0, 2650.0})
    CHECK(lfdm.powertrain.max_torque(rpm * M_PI / 30) == Approx(preset.powertrain.max_torque(rpm * M_PI / 30)));
}

TEST_CASE("rom vehicle files: LFDM keys with a meaning we do not model are refused, not ignored", "[rom]") {
  auto j = nlohmann::json::parse(kLfdmHmmwv);
  const RomVehicle preset = load_rom_vehicle("hmmwv");
  j["c1"] = 0.5;
  CHECK_THROWS_WITH(read_rom_vehicle(j, "HMMWV.json", ".", &preset.tire[0]), Catch::Contains("c1"));
  j = nlohmann::json::parse(kLfdmHmmwv);
  j["nonLinearSteer"] = true;
  CHECK_THROWS_WITH(read_rom_vehicle(j, "HMMWV.json", ".", &preset.tire[0]), Catch::Contains("nonLinearSteer"));
}

TEST_CASE("rom vehicle files: a vehicle written with fitted values loads as those values applied", "[rom]") {
  // What calibrate-rom writes (vehicle_json_with) and what it ran (apply_vary_parameter) must be one
  // vehicle, for every kind of parameter: plain values, scales and the roll stiffness's sum and share.
  const RomVehicle base = load_rom_vehicle("hmmwv");
  const std::vector<std::string> names = {"roll_stiffness_front_share", "roll_stiffness_total", "roll_damping_rear",
                                          "tire_cornering_scale_rear", "torque_scale", "max_steer"};
  const std::vector<double> values = {0.2, 90000, 2500, 0.9, 0.85, 0.8};
  const nlohmann::json written = vehicle_json_with("hmmwv", names, values);
  const RomVehicle read = read_rom_vehicle(nlohmann::json::parse(written.dump()), "written.json");
  RomVehicle applied = base;
  for (std::size_t k = 0; k < names.size(); ++k) apply_vary_parameter(applied, base, names[k], values[k]);
  CHECK(read.roll_stiffness[0] == Approx(18000).epsilon(1e-12));
  CHECK(read.roll_stiffness[1] == Approx(72000).epsilon(1e-12));
  CHECK(applied.roll_stiffness[0] == Approx(read.roll_stiffness[0]).epsilon(1e-12));
  CHECK(applied.roll_stiffness[1] == Approx(read.roll_stiffness[1]).epsilon(1e-12));
  CHECK(read.roll_damping[1] == 2500);
  CHECK(read.max_steer == 0.8);
  for (int l = 0; l < 2; ++l) CHECK(read.tire[1].y[l].df0 == Approx(applied.tire[1].y[l].df0).epsilon(1e-12));
  CHECK(read.powertrain.max_torque.y[3] == Approx(applied.powertrain.max_torque.y[3]).epsilon(1e-12));
}
