#pragma once
// `terracal pipeline-rom`: the vehicle half's loop in one command. The full vehicle drives a training
// set (straight acceleration, step steers left and right, an ISO 3888-1 double lane change) and a
// validation set (a single sine, a constant-steer turn) on rigid ground; a ROM is calibrated on the
// first (calibrate-rom), validated on the second (validate-rom), and every ROM level, preset and
// calibrated, is set against the full vehicle's error and wall time (the accuracy-cost table);
// report.md gathers it.
#include <cstdint>
#include <string>
#include <vector>

#include "rom/rom_batch.hpp"
#include "rom/rom_run.hpp"

namespace terracal::app {

struct RomPipelineSettings {
  std::string vehicle = "hmmwv";  // full vehicle: preset or file
  std::string rom_vehicle;        // the ROM's starting vehicle: "" = `vehicle` (a preset both know)
  rom::RomModel model = rom::RomModel::k18Dof;
  std::string out;
  std::uint64_t seed = 1;
  long max_draws = 3000;  // calibration: draws per chain at most (each draw: two batches of runs of 4 chains)
  long draws = 1000;      // validation: posterior-predictive draws
  rom::BatchDevice device = rom::BatchDevice::kCpu;
  bool plots = true;
};

// One ROM (or the full vehicle) on one manoeuvre: its error against the full vehicle and its cost.
struct AccuracyCostRow {
  std::string maneuver, solver, device;  // solver: "full vehicle", "18dof preset", "18dof calibrated", ...
  double vx_rmse = 0, yaw_rate_rmse = 0;  // against the full vehicle [m/s], [rad/s]
  double wall_per_simulated_second = 0;   // [s/s], per vehicle
};

struct RomPipelineOutcome {
  std::vector<AccuracyCostRow> accuracy_cost;
  bool converged = false;
  double full_seconds = 0, calibration_seconds = 0, validation_seconds = 0, comparison_seconds = 0, total_seconds = 0;
};

RomPipelineOutcome run_rom_pipeline(const RomPipelineSettings& settings);

}  // namespace terracal::app
