#pragma once
// PNG plots of the rigs' curves (gnuplot): bevameter curves with the SCM fit drawn over them, and
// DBP, torque and sinkage against slip for several wheel models. A missing gnuplot is a warning.
#include <string>
#include <utility>
#include <vector>

#include "apps/rig_runs.hpp"
#include "apps/wheel_band.hpp"

namespace terracal::app {

// DIR/PNG drawn by a gnuplot `script` (which sets its own terminal and `set output 'PNG'`) from
// `data` (file name, content) written beside it in a work folder: for reports whose plots are
// assembled by their writer. A missing gnuplot or a failing script is a warning.
void draw_plot(const std::string& dir, const std::string& png, const std::string& script,
               const std::vector<std::pair<std::string, std::string>>& data);

// DIR/bevameter.png: force against sinkage per plate and torque against angle per load; with
// `fit`, the SCM laws of that parameter set as lines.
void plot_bevameter(const std::string& dir, const BevameterCurves& curves, const lowfi::ScmSoil* fit);

// DIR/wheel.png: DBP, torque and sinkage against slip, one line per named model; with `band`, the
// SCM wheel's 90 % posterior band (steady model) shaded behind them.
void plot_wheel_models(const std::string& dir,
                       const std::vector<std::pair<std::string, std::vector<rigs::WheelResult>>>& models,
                       const WheelBand* band = nullptr);
// DIR/trajectory.png from DIR/trajectory.csv: path, speeds, yaw rate and roll, accelerations,
// engine speed and gear.
void plot_trajectory(const std::string& dir, const std::string& title);
// DIR/PNG from DIR/CSV (time, then per channel its reference, preset-ROM and calibrated-ROM columns):
// one panel per channel (name, unit).
void plot_rom_fit(const std::string& dir, const std::string& csv, const std::string& png, const std::string& title,
                  const std::vector<std::pair<std::string, std::string>>& channels);

}  // namespace terracal::app
