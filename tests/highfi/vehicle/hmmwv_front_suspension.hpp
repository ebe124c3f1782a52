#pragma once
// The HMMWV's front double-wishbone suspension, as Chrono's data file
// data/vehicle/hmmwv/suspension/HMMWV_DoubleWishboneFront.json gives it (hardpoints, masses, inertias,
// spring curve, damping), in our suspension format.
#include <nlohmann/json.hpp>

namespace terracal::test {

inline nlohmann::json hmmwv_front_suspension_json() {
  return nlohmann::json::parse(R"({
    "template": "double_wishbone", "name": "HMMWV front",
    "source": "Chrono data/vehicle/hmmwv/suspension/HMMWV_DoubleWishboneFront.json",
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
    "axle_inertia": 0.4
  })");
}

}  // namespace terracal::test
