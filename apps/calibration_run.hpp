#pragma once
// One calibration from curve files to the output folder; shared by `calibrate` and `demo`.
#include <cstdint>
#include <string>

namespace terracal::app {

struct CalibrationRequest {
  std::string plate_csv, shear_csv, priors_json, out_dir;
  std::uint64_t seed = 1;
  int chains = 4;
  double min_ess = 1000;
  long max_draws = 100000;
  std::string sampler = "dram";   // dram | ensemble
  std::string noise = "relative"; // relative | absolute
  bool plots = true;
};

// Validates every input before anything is written (bad input: InputError, no output files),
// then runs the three stages and writes scm_params.json, posterior.h5, summary.txt and the plots.
// Returns 0, or 1 if sampling ended without convergence (the outputs are still written).
int run_calibration(const CalibrationRequest& request);

}  // namespace terracal::app
