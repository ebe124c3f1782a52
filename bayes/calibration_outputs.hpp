#pragma once
// What `terracal calibrate` leaves in its output folder (docs/formats.md): scm_params.json
// (Chrono's SCM block at the MAP point, the posterior summary, the fit), posterior.h5 (ArviZ
// InferenceData), PNG plots, and the summary report. Every file is written under a temporary
// name and renamed.
#include <string>

#include <nlohmann/json.hpp>

#include "bayes/calibration_problem.hpp"
#include "bayes/calibrator.hpp"
#include "bayes/inference_data.hpp"

namespace terracal::bayes {

struct OutputContext {
  std::string sampler;  // "dram" or "ensemble", as scm_params.json names it
  std::uint64_t seed = 0;
  int warmup = 0;
};

// scm_params.json's content: the "Soil parameters" block at the MAP point, "Posterior", "Fit".
nlohmann::ordered_json scm_params_json(const CalibrationProblem& pb, const CalibrationResult& res,
                                       const OutputContext& ctx);
void write_scm_params_json(const std::string& path, const nlohmann::ordered_json& params);

// posterior, sample_stats, observed_data, constant_data, posterior_predictive (at most
// `predictive_draws` draws per chain, evenly thinned).
InferenceData make_inference_data(const CalibrationProblem& pb, const CalibrationResult& res, std::uint64_t seed,
                                  int predictive_draws = 100);

// plate_fit.png, shear_fit.png (and shear_developed.png when such rows exist), pairs.png.
// Returns the files written; throws RunError if gnuplot fails.
std::vector<std::string> write_plots(const std::string& dir, const CalibrationProblem& pb, const CalibrationResult& res,
                                     const InferenceData& idata);

// The human-readable report (also printed on stdout): stages, parameters, diagnostics, notes.
std::string summary_report(const CalibrationProblem& pb, const CalibrationResult& res, const OutputContext& ctx);

}  // namespace terracal::bayes
