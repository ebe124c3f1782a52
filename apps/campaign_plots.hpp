#pragma once
// The campaign report's plots (gnuplot; a missing gnuplot is a warning): the calibrated SCM
// parameters' posterior bands against gravity per soil, the calibrated sets' single-wheel errors per
// entry, the vehicles' speeds on each entry's soil, and the wall time per stage.
#include <map>
#include <string>
#include <vector>

namespace terracal::app {

struct ParameterBand {
  std::string soil;
  double gravity = 0;           // [m/s^2]
  double q05 = 0, q50 = 0, q95 = 0;
};

struct WheelErrors {
  std::string entry;
  double dbp = 0, torque = 0, sinkage = 0;  // RMSE in % of the reference's largest value
};

// DIR/parameters.png: a panel per parameter, median and 90 % interval against gravity, a line per soil.
void plot_parameter_bands(const std::string& dir, const std::vector<std::string>& names,
                          const std::map<std::string, std::vector<ParameterBand>>& bands);
// DIR/wheel_errors.png: drawbar pull, torque and sinkage errors per entry, as grouped bars.
void plot_wheel_errors(const std::string& dir, const std::vector<WheelErrors>& errors);
// A vehicle's speed against time on one entry's soil (the rom stage's trajectory.csv).
struct SpeedTrace {
  std::string entry;  // "sand_g9.81_hmmwv"
  std::vector<double> t, vx;
};
// DIR/rom_speed.png: each entry's speed against time, a line per entry.
void plot_rom_speeds(const std::string& dir, const std::vector<SpeedTrace>& traces);
// DIR/stage_wall.png: total wall time per stage.
void plot_stage_wall(const std::string& dir, const std::vector<std::pair<std::string, double>>& wall);

}  // namespace terracal::app
