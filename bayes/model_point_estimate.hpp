#pragma once
// The first two stages for a simulation-backed problem (model_problem.hpp), each run in batches:
//   1. global search: the start (each parameter's `initial`) and `global_points` points drawn
//      uniformly inside the priors' bounds, run as batches of `batch` and ranked by the posterior
//      with the noise variances profiled out, sum_c (N_c/2) log(SSE_c/N_c) - log prior;
//   2. least squares from the best of them, or from the start and the best few (Ceres, bounded by the priors, residuals
//   divided by each
//      channel's noise scale, re-estimated between rounds until it settles), the Jacobian by central differences of
//      the forward model: one batch of 2 dim runs per Jacobian;
//   3. the Laplace covariance (J^T J)^-1 at the optimum, floored in directions the data leave open,
//      as in point_estimate.hpp, for the samplers' starts and first proposal.
#include <cstdint>

#include "bayes/model_problem.hpp"
#include "bayes/point_estimate.hpp"

namespace terracal::bayes {

struct ModelPointOptions {
  std::uint64_t seed = 1;
  int global_points = 256;  // random points of the global search
  int batch = 256;          // points per forward call in the global search
  // Least-squares starts: 1, the best of the initial point and the global search's; more, the initial
  // point and the global search's starts - 1 best. Each gets one round; the best by the profile
  // objective goes on: one start can settle in a poor basin where the noise weights hold it.
  int starts = 1;
  int polish_rounds = 4;    // at most; rounds stop once the noise scales change by < 1e-9 relative
  int max_iterations = 15;  // Ceres iterations per round
  // Central-difference step, relative to max(|x|, 1e-3 (upper - lower)): large enough to step over
  // the jumps a fixed-step model with discrete events (gear shifts) has at tiny parameter changes.
  double relative_step = 1e-2;
};

// Throws RunError when no point of the global search runs.
PointEstimate estimate_model_point(const ModelProblem& problem, const ModelPointOptions& options);

// Stage 3 alone: est.covariance (and its flags) at est.x, each channel weighted by its noise variance
// times its correlation time. estimate_model_point calls it; call it again after
// ModelProblem::set_correlation_times, else the proposal and the chains' starts keep the white-noise
// width (narrower by sqrt(tau): 16 times on the full-vehicle references).
void laplace_covariance(const ModelProblem& problem, const ModelPointOptions& options, PointEstimate& est);

}  // namespace terracal::bayes
