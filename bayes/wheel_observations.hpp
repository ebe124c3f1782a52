#pragma once
// Single-wheel observations (docs/formats.md, "wheel.csv"): steady drawbar pull, torque and sinkage
// against slip, one row per slip and load, with the wheel they were measured on. Validated once into
// this immutable form; every number in SI units.
#include <string>
#include <vector>

#include "bayes/observations.hpp"

namespace terracal::bayes {

// What the steady SCM wheel needs of the wheel: its rim and its speed (the carriage speed of the
// damping pressure). Grousers are not modelled by the steady wheel.
struct WheelGeometry {
  double radius = 0, width = 0, angular_velocity = 1;
};

struct WheelPoint {
  double slip = 0, load = 0, dbp = 0, torque = 0, sinkage = 0;
  int line = 0;  // line in the file, for messages
};

struct WheelData {
  std::string path;
  WheelGeometry wheel;
  std::vector<WheelPoint> points;
  std::vector<std::string> notes;  // rows kept out and why, for the user
};

// Validates points from any source into a data set. Throws InputError naming the place, value and
// expectation: a slip outside [0, 1) (the steady wheel drives; skids are not modelled), a load <= 0,
// a sinkage < 0 or at least the wheel's radius, a torque or pull that is not finite, two rows for the
// same slip and load, fewer than two rows.
WheelData make_wheel_data(std::vector<WheelPoint> points, const WheelGeometry& wheel, const std::string& source,
                          const PointLocator& where);

// Reads wheel.csv (slip, load_N, dbp_N, torque_Nm, sinkage_m; other columns are ignored). A row whose
// means are NaN (a run without steady means, as `terracal wheel` writes it) is left out with a note;
// every other bad cell is refused.
WheelData load_wheel_csv(const std::string& path, const WheelGeometry& wheel);

}  // namespace terracal::bayes
