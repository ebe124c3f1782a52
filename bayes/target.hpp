#pragma once
// What a sampler explores. A log density over x in R^dim, conditioned on a nuisance vector
// (the noise variances of the calibration) that an exact Gibbs step draws given x. Samplers are
// independent of the calibration problem: the tests run them on textbook targets.
#include <functional>
#include <vector>

#include <Eigen/Dense>

#include "core/rng.hpp"

namespace terracal::bayes {

struct Target {
  int dim = 0;
  int nuisance_dim = 0;  // 0: no nuisance, `gibbs` is never called
  // Optional: the support's box (each bound finite; empty: unbounded or not known). The independence
  // sampler then proposes in unbounded coordinates (box_transform.hpp).
  Eigen::VectorXd lower, upper;
  // log density of x given the nuisance, up to a constant. -inf means outside the support.
  // NaN, +inf or an exception is a failed evaluation: the proposal is rejected and counted,
  // and the chain goes on (a forward model that breaks never aborts a run).
  std::function<double(const Eigen::VectorXd& x, const Eigen::VectorXd& nuisance)> log_density;
  // Draws the nuisance from its exact conditional given x (conjugate update).
  std::function<void(const Eigen::VectorXd& x, Eigen::VectorXd& nuisance, Rng& rng)> gibbs;
  // Optional: the log densities of many points at once, out[i] of (xs[i], nuisances[i]), with the
  // meaning and failure conventions of log_density (a failed point is NaN or +inf). A forward model
  // that runs a simulation per point evaluates them as one batch (threads, or one GPU launch); the
  // ensemble sampler then proposes a whole half of its walkers before evaluating any.
  std::function<void(const std::vector<Eigen::VectorXd>& xs, const std::vector<Eigen::VectorXd>& nuisances,
                     std::vector<double>& out)>
      log_density_batch;
  // Optional: log of the density of each x with the nuisance integrated out over its prior, up to a
  // constant (failures as for log_density). Proposal adaptation (proposal_adaptation.hpp) weighs
  // points by it; without it, by the density given a fixed nuisance.
  std::function<void(const std::vector<Eigen::VectorXd>& xs, std::vector<double>& out)> log_marginal_batch;
};

// Counters a chain keeps; saved in checkpoints.
struct ChainStats {
  long iterations = 0;
  long accepted = 0;            // accepted moves (either delayed-rejection stage)
  long failed_evaluations = 0;  // NaN / +inf / exception from log_density
  double acceptance_rate() const { return iterations ? double(accepted) / double(iterations) : 0.0; }
};

}  // namespace terracal::bayes
