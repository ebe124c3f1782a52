// The built-in full vehicles, in our format (docs/formats.md, "Full vehicle"). Every number comes from
// the Chrono data files each preset names.
#include <string>

#include "highfi/vehicle/full_vehicle.hpp"

namespace terracal::vehicle {
namespace {
constexpr const char* kHmmwv = R"json({
  "type": "full vehicle",
  "name": "HMMWV",
  "source": "Chrono data/vehicle/hmmwv: chassis/HMMWV_Chassis.json, vehicle/HMMWV_Vehicle_4WD.json (suspension and steering locations), steering/HMMWV_PitmanArm.json (maximum angle 50 deg), suspension/HMMWV_DoubleWishboneFront.json and HMMWV_DoubleWishboneRear.json, wheel/HMMWV_Wheel_FrontLeft.json (45.4 kg, 0.113 kg m^2) plus tire/HMMWV_TMeasyTire.json (37.6 kg, [3.84, 6.69, 3.84] kg m^2, vertical damping 3900 N s/m); on SCM the wheel is a cylinder of the tire's radius and the width of HMMWV_RigidTire (10 in); the TMeasy curves and the powertrain as the ROM preset's (Chrono's HMMWV engine, converter and gearbox, final drive in the gear ratios); driveline/HMMWV_Driveline4WD.json (driveshaft 0.5 kg m^2, axle driveshafts 0.5 plus their differential boxes 0.6); the gearbox input's 0.3 kg m^2 is ours",
  "chassis": {"mass": 2086.52, "com": [0.056, 0, 0.523], "inertia": [1078.52, 2955.66, 3570.20]},
  "axles": [
    {"location": [1.688965, 0, 0], "steered": true,
     "suspension": {
      "name": "HMMWV front",
      "spindle": {"mass": 14.705, "com": [-0.040, 0.910, -0.026], "inertia": [0.04117, 0.07352, 0.04117],
                  "radius": 0.15, "width": 0.06},
      "upright": {"mass": 19.450, "com": [-0.040, 0.751, -0.026], "inertia": [0.1656, 0.1934, 0.04367]},
      "upper_arm": {"mass": 5.813, "com": [-0.106, 0.589, 0.218], "inertia": [0.03, 0.03, 0.06276],
                    "chassis_front": [-0.048, 0.446, 0.245], "chassis_back": [-0.268, 0.478, 0.196],
                    "upright": [-0.053, 0.716, 0.215]},
      "lower_arm": {"mass": 23.965, "com": [0.000, 0.547, -0.059], "inertia": [0.4, 0.4, 0.8938],
                    "chassis_front": [0.223, 0.307, 0.000], "chassis_back": [-0.223, 0.307, 0.000],
                    "upright": [-0.036, 0.787, -0.118]},
      "tierod": {"chassis": [-0.250, 0.448, 0.054], "upright": [-0.176, 0.821, -0.016]},
      "spring": {"chassis": [0.104, 0.510, 0.197], "arm": [0.097, 0.543, -0.047], "free_length": 0.339,
                 "curve": [[-0.2, -322095.536], [-0.18, -240521.166], [-0.16, -174535.686], [-0.14, -122406.996],
                           [-0.12, -82402.997], [-0.1, -52791.592], [-0.08, -31840.681], [-0.06, -17818.165],
                           [-0.04, -8991.945], [-0.02, -3629.923], [0, 0], [0.02, 3629.923], [0.04, 8991.945],
                           [0.06, 17818.165], [0.08, 31840.681], [0.1, 52791.592], [0.12, 82402.997],
                           [0.14, 122406.996], [0.16, 174535.686], [0.18, 240521.166], [0.2, 322095.536]]},
      "shock": {"chassis": [0.104, 0.498, 0.323], "arm": [0.097, 0.543, -0.047], "damping": 19015.5692},
      "axle_inertia": 0.4}},
    {"location": [-1.688965, 0, 0],
     "suspension": {
      "name": "HMMWV rear",
      "spindle": {"mass": 14.705, "com": [0.036, 0.910, -0.026], "inertia": [0.04117, 0.07352, 0.04117],
                  "radius": 0.15, "width": 0.06},
      "upright": {"mass": 19.450, "com": [0.036, 0.751, -0.026], "inertia": [0.1656, 0.1934, 0.04367]},
      "upper_arm": {"mass": 5.813, "com": [0.124, 0.589, 0.221], "inertia": [0.03, 0.03, 0.06276],
                    "chassis_front": [0.349, 0.462, 0.228], "chassis_back": [0.077, 0.462, 0.224],
                    "upright": [0.036, 0.716, 0.216]},
      "lower_arm": {"mass": 23.965, "com": [0.000, 0.547, -0.059], "inertia": [0.4, 0.4, 0.8938],
                    "chassis_front": [0.223, 0.307, 0.000], "chassis_back": [-0.223, 0.307, 0.000],
                    "upright": [0.036, 0.787, -0.118]},
      "tierod": {"chassis": [0.223, 0.416, 0.059], "upright": [0.170, 0.821, -0.009]},
      "spring": {"chassis": [-0.104, 0.502, 0.256], "arm": [-0.097, 0.543, -0.047], "free_length": 0.382,
                 "curve": [[-0.2, -711719.272], [-0.18, -531468.245], [-0.16, -385663.250], [-0.14, -270476.949],
                           [-0.12, -182082.006], [-0.1, -116651.084], [-0.08, -70356.846], [-0.06, -39371.956],
                           [-0.04, -19869.076], [-0.02, -8020.869], [0, 0], [0.02, 8020.869], [0.04, 19869.076],
                           [0.06, 39371.956], [0.08, 70356.846], [0.1, 116651.084], [0.12, 182082.006],
                           [0.14, 270476.949], [0.16, 385663.250], [0.18, 531468.245], [0.2, 711719.272]]},
      "shock": {"chassis": [-0.104, 0.498, 0.323], "arm": [-0.097, 0.544, -0.038], "damping": 36725.2201},
      "axle_inertia": 0.4}}
  ],
  "steering": {
    "template": "pitman_arm", "name": "HMMWV Pitman arm",
    "link": {"mass": 9.072, "com": [0.129, 0, 0], "inertia": [1, 1, 1]},
    "arm": {"mass": 2.259, "com": [0.064, 0.249, 0], "inertia": [1, 1, 1]},
    "revolute": {"point": [0, 0.249, 0], "axis": [0, 0, 1], "max_angle": 0.872664626},
    "universal": {"point": [0.129, 0.249, 0], "axis_arm": [0, 0, 1], "axis_link": [1, 0, 0]},
    "idler": {"chassis": [0, -0.325, 0], "link": [0.129, -0.325, 0], "axis": [0, 0, 1]},
    "location": [1.24498, 0, 0.101322], "orientation": [0.98699637, 0, 0.16074256, 0]},
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
    "max_brake_torque": 4000},
  "driveline": {"turbine_inertia": 0.3, "driveshaft_inertia": 0.5, "axle_driveshaft_inertia": 1.1},
  "wheel": {"mass": 83.0, "inertia": [3.953, 6.803, 3.953], "width": 0.254},
  "tire": {
    "type": "TMeasy", "unloaded_radius": 0.4699, "wheel_inertia": 6.803, "vertical_stiffness": 411121.0,
    "rolling_resistance": 0.015, "nominal_load": 8562.8266, "max_load": 29969.893,
    "longitudinal_stiffness": 185004.42, "lateral_stiffness": 164448.37,
    "longitudinal_damping": 3700, "lateral_damping": 3488, "rdyn_coefficient": [0.375, 0.75],
    "longitudinal": {"df0": [151447.29, 236412.79], "fm": [7575.3614, 12808.276], "sm": [0.12, 0.15],
                     "fs": [4657.9208, 8625.3352], "ss": [0.9, 0.95]},
    "lateral": {"df0": [50931.693, 94293.847], "fm": [6615.0404, 12509.947], "sm": [0.38786, 0.38786],
                "fs": [6091.5092, 11443.875], "ss": [0.82534, 0.91309]}},
  "tire_vertical_damping": 3900
})json";
}  // namespace

std::string full_vehicle_preset_json(const std::string& name) { return name == "hmmwv" ? kHmmwv : ""; }

}  // namespace terracal::vehicle
