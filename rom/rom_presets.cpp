// The built-in vehicles (--vehicle hmmwv | sedan), in our vehicle format. Every number comes from
// the LFDM data files named in "source" (uwsbel/low-fidelity-dynamic-models, which took them from
// Chrono's HMMWV and sedan models); maps in rpm as there.
#include <string>

#include "rom/rom_vehicle_json.hpp"

namespace terracal::rom {

namespace {

constexpr const char* kHmmwv = R"json({
  "type": "ROM vehicle",
  "name": "HMMWV",
  "source": "LFDM wheeled_vehicle_models/18dof/data/json/HMMWV.json and TMeasy.json (Chrono HMMWV); pitch inertia and suspension from 24dof-gpu/data/json/HMMWV/vehicle.json and suspension.json",
  "effects": ["tire_relaxation", "torque_converter", "roll", "rolling_resistance"],
  "mass": 2097.85, "unsprung_mass": [139.133, 139.133],
  "cg_to_front": 1.6889, "cg_to_rear": 1.6889, "cg_height": 0.713,
  "yaw_inertia": 4519, "roll_inertia": 1289, "pitch_inertia": 3718.28, "track": [1.82, 1.82],
  "spring_rate": 150000, "damper_rate": 19015.5692,
  "roll_center_height": [0.379, 0.327], "roll_stiffness": [31000, 31000], "roll_damping": [3300, 3300],
  "max_steer": 0.6525249,
  "powertrain": {
    "drive": "all", "crank_inertia": 1.093,
    "max_torque_rpm": [[-100, 258.0], [800, 328.52], [900, 421.4], [1000, 497.94], [1100, 559.0], [1200, 607.16],
                       [1300, 641.56], [1400, 665.64], [1500, 678.54], [1600, 681.98], [1700, 677.68], [1800, 665.64],
                       [1900, 648.44], [2000, 626.08], [2100, 599.42], [2200, 571.04], [2300, 540.08], [2400, 509.98],
                       [2500, 479.88], [2700, -344.0]],
    "losses_rpm": [[-50, 30], [0, 0], [50, -30], [1000, -50], [2000, -70], [3000, -90]],
    "capacity_factor": [[0.0, 15.0], [0.25, 15.0], [0.5, 15.0], [0.75, 16.0], [0.9, 18.0], [1.0, 35.0]],
    "torque_ratio": [[0.0, 2.0], [0.25, 1.8], [0.5, 1.5], [0.75, 1.15], [1.0, 1.0]],
    "gear_ratios": [0.04, 0.08, 0.16], "upshift_rpm": 2500, "downshift_rpm": 1200,
    "max_brake_torque": 4000
  },
  "tire": {
    "type": "TMeasy", "unloaded_radius": 0.4699, "wheel_inertia": 6.5, "vertical_stiffness": 411121.0,
    "rolling_resistance": 0.015, "nominal_load": 8562.8266, "max_load": 29969.893,
    "longitudinal_stiffness": 185004.42, "lateral_stiffness": 164448.37,
    "longitudinal_damping": 3700, "lateral_damping": 3488, "rdyn_coefficient": [0.375, 0.75],
    "longitudinal": {"df0": [151447.2, 236412.79], "fm": [7575.3614, 12808.276], "sm": [0.12, 0.15],
                     "fs": [4657.9208, 8625.3352], "ss": [0.9, 0.95]},
    "lateral": {"df0": [50931.693, 94293.84], "fm": [6615.0404, 12509.947], "sm": [0.38786, 0.38786],
                "fs": [6091.5092, 11443.875], "ss": [0.82534, 0.91309]}
  }
})json";

constexpr const char* kSedan = R"json({
  "type": "ROM vehicle",
  "name": "sedan",
  "source": "LFDM wheeled_vehicle_models/18dof/data/json/Sedan/vehicle.json and sedan_TMeasy.json (Chrono sedan); pitch inertia and suspension from 24dof-gpu/data/json/Sedan/vehicle.json and 24dof/data/json/Sedan/suspension.json",
  "effects": ["tire_relaxation", "roll", "rolling_resistance"],
  "mass": 1671.26, "unsprung_mass": [54.543, 54.543],
  "cg_to_front": 1.388, "cg_to_rear": 1.388, "cg_height": 0.3,
  "yaw_inertia": 1242.33, "roll_inertia": 296.868, "pitch_inertia": 1119.47, "track": [1.5958, 1.5958],
  "spring_rate": 500000, "damper_rate": 10000,
  "roll_center_height": [0.41, 0.40], "roll_stiffness": [60000, 60000], "roll_damping": [3300, 3300],
  "max_steer": 0.69,
  "powertrain": {
    "drive": "all", "crank_inertia": 1.0,
    "max_torque_rpm": [[-10, 125.568], [1000, 284.16], [1200, 355.2], [1400, 405.96], [1500, 426.24], [1600, 444.0],
                       [2000, 444.0], [2500, 444.0], [3000, 444.0], [3500, 444.0], [4000, 444.0], [4500, 444.0],
                       [4600, 443.16], [4800, 436.8], [5000, 424.0], [5200, 407.64], [5500, 385.44], [5700, 371.88],
                       [6000, 353.28], [6200, 336.48], [6500, 293.52]],
    "losses_rpm": [[-50, 30], [0, 0], [50, -10], [1000, -10], [2000, -15], [3000, -15], [3500, -20], [4000, -20],
                   [4500, -30], [5000, -50], [6000, -70], [6500, -100]],
    "capacity_factor": [[0.0, 15.0], [0.25, 15.0], [0.5, 15.0], [0.75, 16.0], [0.9, 18.0], [1.0, 35.0]],
    "torque_ratio": [[0.0, 2.0], [0.25, 1.8], [0.5, 1.5], [0.75, 1.15], [1.0, 1.0]],
    "gear_ratios": [0.053, 0.0978, 0.1568, 0.2126, 0.2552, 0.2998],
    "upshift_rpm": [4000, 4500, 4500, 4500, 4500, 4500], "downshift_rpm": [1000, 1200, 1400, 1600, 1800, 2000],
    "max_brake_torque": 2000
  },
  "tire": {
    "type": "TMeasy", "unloaded_radius": 0.3266, "wheel_inertia": 4, "vertical_stiffness": 411121.0,
    "rolling_resistance": 0.015, "nominal_load": 8562.8266, "max_load": 29969.893,
    "longitudinal_stiffness": 185004.42, "lateral_stiffness": 164448.37,
    "longitudinal_damping": 3700, "lateral_damping": 3488, "rdyn_coefficient": [0.375, 0.75],
    "longitudinal": {"df0": [142057.4736, 221755.19702], "fm": [7575.3614, 12808.276], "sm": [0.12, 0.15],
                     "fs": [4657.9208, 8625.3352], "ss": [0.9, 0.95]},
    "lateral": {"df0": [56024.8623, 103723.224], "fm": [6615.0404, 12509.947], "sm": [0.38786, 0.38786],
                "fs": [6091.5092, 11443.875], "ss": [0.82534, 0.91309]}
  }
})json";

}  // namespace

std::string rom_preset_json(const std::string& name) {
  if (name == "hmmwv") return kHmmwv;
  if (name == "sedan") return kSedan;
  return "";
}

}  // namespace terracal::rom
