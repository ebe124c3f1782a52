#pragma once
// One calibration, from its data to the output folder; shared by `calibrate`, `demo` and `pipeline`.
// The data come from curve files (`calibrate`) or from the rigs' curves in memory (`pipeline`).
#include <cstdint>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "apps/rig_runs.hpp"
#include "bayes/calibration_problem.hpp"
#include "bayes/calibrator.hpp"
#include "bayes/observations.hpp"
#include "bayes/priors.hpp"
#include "bayes/wheel_observations.hpp"
#include "core/range.hpp"
#include "lowfi/scm_soil.hpp"

namespace terracal::app {

// The allowed values of the calibration's options, checked on the command line and by
// run_calibration. At least 4 chains, so that split R-hat compares 8 half-chains from dispersed
// starts. The draws are kept in memory (about 10 doubles per draw and chain, twice): the cap of 1e8
// per chain keeps a run that never converges from growing without bound (the demo converges after a
// few thousand).
struct CalibrationRanges {
  static constexpr long long kMinChains = 4, kMaxChains = 256;
  static constexpr long long kMinDraws = 10, kMaxDraws = 100000000;
  static constexpr Range kMinEss{0, 1e9, true, false};
  static constexpr Range kElasticStiffness{1, 1e13, false, false, "Pa/m"};  // as the SCM soil reader's
};

// The options of one calibration (docs/architecture.md, "Calibration").
struct CalibrationSettings {
  std::string out_dir;
  std::uint64_t seed = 1;
  int chains = 4;
  double min_ess = 1000;
  long max_draws = 100000;
  bayes::SamplerKind sampler = bayes::SamplerKind::kDram;
  bayes::NoiseModel noise = bayes::NoiseModel::kRelative;
  // Count each test type as N / tau rows, tau from its residuals' lag-one correlation at a first
  // least-squares point (bayes/correlation_time.hpp); false: every row independent.
  bool correlated_noise = false;
  // With bevameter and wheel curves: the annulus's law is the set's (shared) or the set's with its
  // strength over a fitted ratio R and its own Janosi k (scaled; bayes/calibration_problem.hpp).
  bayes::AnnulusLaw annulus_law = bayes::AnnulusLaw::kShared;
  // The set's SCM elastic stiffness [Pa/m]; 0: fitted to the plates' unload rows (Chrono's default
  // without them).
  double elastic_stiffness = 0;
  bool plots = true;
};

// What is calibrated: the plate data, optionally the shear data and single-wheel curves, and the priors.
struct CalibrationData {
  bayes::PlateData plate;
  std::optional<bayes::ShearData> shear;
  bayes::Priors priors = bayes::default_priors();
  std::optional<bayes::WheelData> wheel;
};

// The curve files of `calibrate`: plate (required), shear, wheel and priors (optional, "" = none).
// The wheel's geometry comes from wheel_spec (a wheel file), or else from the run.json that
// `terracal wheel` wrote beside wheel.csv.
struct CalibrationFiles {
  std::string plate_csv, shear_csv, priors_json, wheel_csv, wheel_spec;
};
CalibrationData read_calibration_files(const CalibrationFiles& files);

// The rigs' curves as they are in memory, validated as the files would be; `dir` is where the
// pipeline wrote the same rows (plate.csv, shear.csv), which messages cite by line.
CalibrationData calibration_data(const BevameterCurves& curves, const std::string& dir);
// A wheel sweep's steady means in memory as calibration data (rows at `slips` only, when given), cited
// as `csv` (where the same rows were written).
bayes::WheelData wheel_calibration_data(const std::vector<rigs::WheelResult>& runs, const rigs::WheelSpec& wheel,
                                        const std::string& csv, const std::vector<double>& slips = {});
// The steady SCM wheel's geometry of a rig's wheel (grousers are not modelled; a warning says so).
bayes::WheelGeometry wheel_geometry(const rigs::WheelSpec& wheel, const std::string& where);

struct CalibrationOutcome {
  bool converged = false;
  lowfi::ScmSoil fitted;          // the MAP set, validated as an SCM soil
  nlohmann::ordered_json params;  // scm_params.json as written
  // Posterior draws as SCM sets (with the fitted Ke, Chrono's damping and S), evenly thinned to at
  // most kPosteriorSets per chain: what a predictive band runs through a fast model.
  std::vector<lowfi::ScmSoil> posterior_sets{};
};
inline constexpr int kPosteriorSets = 25;

// Validates the settings before anything is written (bad input: InputError, no output files), then
// runs the three stages and writes scm_params.json, posterior.h5, summary.txt and the plots. When
// sampling ends without convergence the outputs are still written and `converged` is false.
CalibrationOutcome run_calibration(const CalibrationData& data, const CalibrationSettings& settings);

// The sampler's and noise model's names as the options and scm_params.json spell them.
std::string sampler_name(bayes::SamplerKind kind);
std::string noise_name(bayes::NoiseModel model);

}  // namespace terracal::app
