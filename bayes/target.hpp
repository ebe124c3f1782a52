#pragma once
// What a sampler explores. A log density over x in R^dim, conditioned on a nuisance vector
// (the noise variances of the calibration) that an exact Gibbs step draws given x. Samplers are
// independent of the calibration problem: the tests run them on textbook targets.
#include <functional>

#include <Eigen/Dense>

#include "core/rng.hpp"

namespace terracal::bayes {

struct Target {
  int dim = 0;
  int nuisance_dim = 0;  // 0: no nuisance, `gibbs` is never called
  // log density of x given the nuisance, up to a constant. -inf means outside the support.
  // NaN, +inf or an exception is a failed evaluation: the proposal is rejected and counted,
  // and the chain goes on (a forward model that breaks never aborts a run).
  std::function<double(const Eigen::VectorXd& x, const Eigen::VectorXd& nuisance)> log_density;
  // Draws the nuisance from its exact conditional given x (conjugate update).
  std::function<void(const Eigen::VectorXd& x, Eigen::VectorXd& nuisance, Rng& rng)> gibbs;
};

// Counters a chain keeps; saved in checkpoints.
struct ChainStats {
  long iterations = 0;
  long accepted = 0;            // accepted moves (either delayed-rejection stage)
  long failed_evaluations = 0;  // NaN / +inf / exception from log_density
  double acceptance_rate() const { return iterations ? double(accepted) / double(iterations) : 0.0; }
};

}  // namespace terracal::bayes
