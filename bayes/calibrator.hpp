#pragma once
// The calibrator: curves in, posterior out. Three stages, modelled on Ceres' Solve/Summary:
//   1. global search (NLopt) and least-squares polish (Ceres) -> MAP point and covariance;
//   2. MCMC from dispersed starts around the MAP, the Ceres covariance as the first proposal:
//      DRAM chains (default) or the affine-invariant ensemble, the noise variances by Gibbs steps;
//   3. blocks of draws until every free parameter has rank-normalised split R-hat below
//      max_rhat and bulk ESS of at least min_ess, or the draw cap (reported as not converged).
// A checkpoint after warm-up and after every block holds the chains' complete state, RNG
// included: a killed run started again with the same checkpoint ends with exactly the draws of
// an uninterrupted one. A corrupt or foreign checkpoint (core/checkpoint_file.hpp) is reported
// through `progress` ("restarted") and the run starts over.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "bayes/calibration_problem.hpp"
#include "bayes/diagnostics.hpp"
#include "bayes/point_estimate.hpp"

namespace terracal::bayes {

// DRAM chains, the affine-invariant ensemble, or independence Metropolis-Hastings chains with a
// t proposal fitted to the Laplace approximation (independence.hpp: for simulation-backed targets,
// one batch of runs per step).
enum class SamplerKind { kDram, kEnsemble, kIndependence };

struct CalibrationProgress {
  // "adapted" (the independence proposal; `message` says how), "resumed" or "restarted" (a
  // checkpoint was found; `message` says what of it), then "warm-up" and "sampling" (after each block).
  std::string stage;
  long draws_per_chain = 0;
  double max_rhat = 0, min_ess = 0;
  std::string message;
};

struct CalibrationOptions {
  std::uint64_t seed = 1;
  int chains = 4;  // DRAM chains; the ensemble uses max(chains, 2 dim + 2) walkers (even)
  SamplerKind sampler = SamplerKind::kDram;
  // DRAM: run the chains in the box's unbounded coordinates (box_transform.hpp) where the target has
  // a box, as the independence sampler does; draws are recorded in the target's own coordinates.
  // For posteriors with long tails towards a bound (a Janosi k that only a few wheel rows pin).
  bool dram_in_box = false;
  double min_ess = 1000;        // bulk ESS per parameter
  double max_rhat = 1.01;       // rank-normalised split R-hat per parameter
  int warmup = 1000;            // iterations per chain with adaptation, discarded
  int block = 500;              // iterations per chain between convergence checks / checkpoints
  // Blocks grow to a quarter of the draws so far (checks and checkpoints then cost O(N log N) over a
  // long run); false: a check every `block` iterations, for samplers whose iterations are few and
  // each far dearer than a check (i-SIR: a GPU launch per step).
  bool growing_blocks = true;
  long max_draws = 100000;      // per chain; reaching it ends the run as not converged
  std::string checkpoint_path;  // empty: no checkpoint
  std::string fingerprint;      // identifies data + options; a checkpoint with another is reported and ignored
  int global_evaluations = 20000;
  // Independence sampler: rounds of importance sampling that move the proposal from the Laplace
  // approximation onto the posterior before the chains start (proposal_adaptation.hpp); 0: none.
  // Rounds stop once the proposal reaches the posterior (4 on the full-vehicle references from a
  // good least-squares point); from a point with parameters on their bounds it took 27.
  int adaptation_rounds = 30;
  bool local_moves = true;  // independence sampler: a random-walk move after each independence move
  // Independence sampler: points per chain and step (1: Metropolis-Hastings; more: i-SIR, one batch of
  // chains x (tries - 1) runs per step, for a GPU; bayes/independence.hpp).
  int tries = 1;
  // Independence sampler: steps whose proposals are evaluated as one batch (IndependenceOptions::
  // lookahead; for a GPU that holds several steps' runs in one launch). Needs a collapsed target.
  int lookahead = 1;
  // Independence sampler with local moves: each random-walk move is first tested on a surrogate of the
  // posterior (a t with the adapted proposal's mean and covariance), and only the moves that pass it
  // run (IndependenceOptions::delayed_acceptance; the target stays exact).
  bool delayed_acceptance = false;
  int adaptation_points = 256;  // runs per round of importance sampling (one batch)
  // Rounds at the posterior's own weights continue until the weights' ESS over all rounds reaches
  // this (proposal_adaptation.hpp); 0: the first such round ends adaptation.
  double adaptation_final_ess = 0;
  double proposal_scale = 1.3;  // independence sampler: proposal covariance = scale^2 x the adapted one
  std::function<void(const CalibrationProgress&)> progress;  // called after warm-up and each block
};

struct CalibrationResult {
  PointEstimate point;
  std::vector<std::string> names;  // free parameters (short names), then "sigma2_<type>"
  int num_params = 0;              // how many of `names` are SCM parameters
  int chains = 0;
  long draws = 0;  // per chain, after warm-up
  // draws[c][d * names.size() + v]; lp[c][d]; accepted[c][d] (0/1: did the step move)
  std::vector<std::vector<double>> values, lp, accepted;
  std::vector<VariableSummary> summary;  // per name
  bool converged = false;
  bool resumed = false;
  long failed_evaluations = 0;
  double acceptance_rate = 0;
  std::string termination;         // why sampling stopped, in words
  std::vector<std::string> notes;  // what the user should know about this run

  // All draws of variable v, per chain (for diagnostics and plots).
  Chains chains_of(int v) const;
};

CalibrationResult calibrate(const CalibrationProblem& problem, const CalibrationOptions& options);

// Stage 2 and 3 alone, for any target (the SCM problem's, or a simulation-backed one): `res` comes
// with its point estimate (x, covariance, noise_var, unconstrained_directions), `names` (the target's
// free parameters, then its noise variances) and `num_params`; the draws, diagnostics and
// termination are added to it.
void sample_posterior(const Target& target, const CalibrationOptions& options, CalibrationResult& res);

}  // namespace terracal::bayes
