#pragma once
// What a simulation-backed calibration (model_problem.hpp) leaves for its caller to write: the
// posterior as ArviZ InferenceData and the per-parameter summary as JSON, in the layout of the SCM
// calibration's files (calibration_outputs.hpp), so the same tools read both.
#include <cstdint>

#include <nlohmann/json.hpp>

#include "bayes/calibrator.hpp"
#include "bayes/inference_data.hpp"
#include "bayes/model_problem.hpp"

namespace terracal::bayes {

// posterior (each parameter and sigma2_<channel>), sample_stats, observed_data (<channel>, dimension
// <channel>_obs), constant_data (<channel>_time, <channel>_curve), posterior_predictive (at most
// `predictive_draws` draws per chain, evenly thinned, run as one forward batch, plus noise).
InferenceData make_model_inference_data(const ModelProblem& pb, const CalibrationResult& res, std::uint64_t seed,
                                        int predictive_draws = 50);

// {"<parameter>": {"mean", "sd", "q05", "q50", "q95", "rhat", "ess_bulk", "map", "unit"}, ...} for the
// parameters and the noise variances.
nlohmann::ordered_json model_posterior_json(const ModelProblem& pb, const CalibrationResult& res);

// The parameters' draws as rows of parameter vectors, every chain's in turn.
std::vector<Eigen::VectorXd> parameter_draws(const CalibrationResult& res);

}  // namespace terracal::bayes
