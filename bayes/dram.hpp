#pragma once
// Delayed-rejection adaptive Metropolis (DRAM) of Haario, Laine, Mira & Saksman (2006),
// "DRAM: efficient adaptive MCMC", Statistics and Computing 16:339-354.
// Adaptation (AM, Haario et al. 2001) learns the posterior covariance, which matters here because
// the soil parameters differ by eight orders of magnitude and are strongly correlated; delayed
// rejection (Mira 2001) rescues the many rejections of an early, badly scaled proposal.
#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include "bayes/running_covariance.hpp"
#include "bayes/target.hpp"
#include "core/rng.hpp"

namespace terracal::bayes {

struct DramOptions {
  int adapt_start = 100;          // iterations before the covariance starts to adapt
  double scale = 0;               // proposal scale s_d; 0 means 2.38^2 / dim
  double dr_scale = 0.1;          // second-stage proposal covariance = dr_scale * first-stage
  double regularisation = 1e-10;  // relative to each diagonal element of the adapted covariance
};

class DramChain {
 public:
  // `target` must outlive the chain. Throws std::invalid_argument on sizes that do not match the
  // target, a proposal covariance that is not positive definite, or an initial point whose log
  // density is not finite.
  DramChain(const Target& target, const DramOptions& opt, Eigen::VectorXd x0, Eigen::VectorXd nuisance0,
            const Eigen::MatrixXd& proposal_covariance, Rng rng);

  // One two-stage DR Metropolis move on x, then the Gibbs update of the nuisance (when there is
  // one), then (if adapt) the covariance update of the proposal.
  void step(bool adapt);

  const Eigen::VectorXd& x() const { return x_; }
  const Eigen::VectorXd& nuisance() const { return nuisance_; }
  double log_density() const { return logp_; }  // of x given the current nuisance
  const ChainStats& stats() const { return stats_; }
  Eigen::MatrixXd proposal_covariance() const { return chol_ * chol_.transpose(); }

  // Everything that a continuation needs to draw bit-identically. load() expects a chain built
  // with the same Target and options; it replaces the whole state.
  nlohmann::json save() const;
  void load(const nlohmann::json& j);

 private:
  bool delayed_rejection_move();
  bool second_stage(const Eigen::VectorXd& z1, double lp1);
  void gibbs_update();
  void adapt_proposal();
  void move_to(const Eigen::VectorXd& y, double lp);

  const Target* target_;
  DramOptions opt_;
  Eigen::VectorXd x_, nuisance_;
  double logp_ = 0;
  Eigen::MatrixXd chol_;  // lower Cholesky factor of the first-stage proposal covariance
  RunningCovariance adaptation_;
  ChainStats stats_;
  Rng rng_;
};

}  // namespace terracal::bayes
