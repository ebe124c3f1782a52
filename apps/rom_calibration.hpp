#pragma once
// `terracal calibrate-rom`: a reduced-order vehicle's parameters fitted to reference runs (of the
// full vehicle, or any run with trajectory.csv and inputs.txt), with their posterior. The ROM runs
// as the calibrator's batch forward model (rom/rom_forward.hpp, bayes/model_problem.hpp).
#include <cstdint>
#include <string>
#include <vector>

#include "bayes/calibrator.hpp"
#include "bayes/model_problem.hpp"
#include "rom/rom_batch.hpp"
#include "rom/rom_reference.hpp"
#include "rom/rom_vehicle.hpp"

namespace terracal::app {

struct RomCalibrationSettings {
  rom::RomModel model = rom::RomModel::k18Dof;
  std::string vehicle;                  // preset or vehicle file
  std::vector<std::string> references;  // folders
  std::string params_json;              // "": the default parameters and priors
  std::string out;
  std::uint64_t seed = 1;
  bayes::SamplerKind sampler = bayes::SamplerKind::kIndependence;  // or kEnsemble
  int chains = 0;  // chains (ensemble: walkers); 0: 4, 24 with tries > 1 (ensemble: 2 (parameters + 1))
  // Independence sampler: points per chain and step; 1: Metropolis-Hastings, more: i-SIR, one batch of
  // chains x (tries - 1) runs per step; 0: 1 on the CPU, 96 on a GPU (docs/decisions.md, "ROM
  // calibration on a GPU").
  int tries = 0;
  // Independence sampler: steps whose proposals go into one batch (they do not depend on the chains'
  // states); 0: as many as one GPU launch holds at once with i-SIR on a GPU, else 1.
  int lookahead = 0;
  // Independence sampler, Metropolis-Hastings: random-walk moves first tested on a surrogate of the
  // posterior (a t fitted to it), only those that pass it run; -1: on with tries 1 (docs/decisions.md,
  // "Delayed acceptance"), 0 off, 1 on.
  int delayed_acceptance = -1;
  double min_ess = 400;  // bulk ESS per parameter
  double max_rhat = 1.01;
  long max_draws = 20000;  // per walker
  int warmup = -1;         // steps per chain; -1: 40, 10 with tries > 1 (ensemble: 300 is a better start)
  int global_points = 256;
  int starts = 3;      // least-squares solves from the global search's best points
  double step = 1e-3;  // the ROM's half-implicit step [s]
  rom::BatchDevice device = rom::BatchDevice::kCpu;
  bool plots = true;
  // Residuals correlated along a run: each channel counts as N / tau independent rows, tau from the
  // residuals at the least-squares point (bayes/model_problem.hpp); false: every row independent.
  bool correlated_noise = true;
};

// The parameters to fit, with priors: the vehicle parameters a reference run informs (docs/rom.md,
// "Calibration"). Those of effects the vehicle does not simulate are left out.
std::vector<bayes::ModelParameter> default_rom_parameters(rom::RomModel model, const rom::RomVehicle& base);

// P.json: {"<parameter>": {"type": "uniform", "lower": .., "upper": ..}, ...}, the same prior types as
// `calibrate --priors`; it names exactly the parameters to fit ("fixed" ones are set, not fitted:
// `fixed` receives them). Throws InputError naming the file, key, value and range.
std::vector<bayes::ModelParameter> read_rom_parameters(const std::string& path, rom::RomModel model,
                                                       const rom::RomVehicle& base,
                                                       std::vector<std::pair<std::string, double>>& fixed);

// The compared channels of the references, flattened for the calibrator (roll is left out for the
// 11-DOF model, which has none, and where a reference lacks it).
std::vector<bayes::ModelChannel> rom_channels(const std::vector<rom::RomReference>& refs, rom::RomModel model,
                                              std::vector<rom::RomChannel>& which);

struct RomCalibrationOutcome {
  bayes::CalibrationResult result;
  std::vector<std::string> parameters;
  double wall_seconds = 0;
  long runs = 0, failed_runs = 0;
  double forward_seconds = 0;   // spent in the batch runs
  double stepping_seconds = 0;  // of which stepping the vehicles
  double model_seconds = 0;     // in the forward model: the batches, building vehicles, resampling
};

// Runs the calibration and writes rom_params.json, posterior.h5, fit_<reference>.csv and
// fit_<reference>.png into settings.out.
RomCalibrationOutcome run_rom_calibration(const RomCalibrationSettings& settings);

}  // namespace terracal::app
