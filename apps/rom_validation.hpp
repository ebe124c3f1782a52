#pragma once
// `terracal validate-rom`: posterior-predictive runs of a calibrated reduced-order vehicle (the output
// folder of `terracal calibrate-rom`) on reference manoeuvres it was not fitted to. N parameter draws
// of posterior.h5 run on each reference as one batch (rom/rom_forward.hpp); per reference and channel
// the RMSE of the MAP vehicle, of the median prediction and of the preset vehicle, and the coverage
// of the 90 % bands: the model band (the predictions alone) and the posterior predictive band (each
// draw's prediction plus noise of that draw's variance sigma2_<channel>).
#include <cstdint>
#include <string>
#include <vector>

#include "rom/rom_batch.hpp"
#include "rom/rom_reference.hpp"

namespace terracal::app {

struct RomValidationSettings {
  std::string posterior;                // calibrate-rom's output folder (rom_params.json, posterior.h5)
  std::vector<std::string> references;  // folders with trajectory.csv and inputs.txt
  long draws = 10000;                   // parameter draws, with replacement
  std::uint64_t seed = 1;
  bool seed_given = false;  // false: the calibration's seed (rom_params.json "Fit"/"seed")
  rom::BatchDevice device = rom::BatchDevice::kCpu;
  std::string out;  // "": <posterior>/validation
  bool plots = true;
};

// Draws x rows x channels doubles of one reference above this are refused (InputError).
inline constexpr std::uint64_t kRomValidationMaxBytes = std::uint64_t{2} << 30;

// One channel of one reference: the bands at each reference time, and the scores.
struct RomChannelValidation {
  rom::RomChannel channel = rom::kRcVx;
  std::vector<double> reference, map, preset;             // map, preset: empty when that run failed
  std::vector<double> median, q05, q95;                   // of the model predictions (no noise)
  std::vector<double> pred_q05, pred_q95;                 // of the predictions plus each draw's noise
  double rmse_map = 0, rmse_median = 0, rmse_preset = 0;  // NaN where the run failed
  double coverage_model = 0, coverage_predictive = 0;     // fraction of reference samples in [q05, q95]
};

struct RomReferenceValidation {
  std::string name, dir;
  std::vector<double> time;
  std::vector<RomChannelValidation> channels;
  long failed_runs = 0;     // draws whose run failed (left out of the quantiles)
  double wall_seconds = 0;  // the draws' batch
};

struct RomValidationOutcome {
  std::string model, vehicle, device, out;
  std::vector<std::string> parameters;
  std::vector<rom::RomChannel> channels;
  long draws = 0, available_draws = 0;  // drawn; chains x draws in posterior.h5
  std::uint64_t seed = 0;
  double step = 0;
  std::vector<RomReferenceValidation> references;
  double batch_seconds = 0, wall_seconds = 0;
  long failed_runs = 0;
};

// Reads the posterior, runs the draws, the MAP and the preset vehicle on each reference, and writes
// report.md, summary.json, band_<reference>.csv and (with plots) band_<reference>.png into the output
// folder (made if missing). InputError for a missing or foreign rom_params.json or posterior.h5, a
// reference lacking a compared channel, or draws that would need more than kRomValidationMaxBytes;
// RunError when every draw fails on a reference.
RomValidationOutcome run_rom_validation(const RomValidationSettings& settings);

}  // namespace terracal::app
