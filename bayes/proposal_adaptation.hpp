#pragma once
// Adaptive importance sampling for the independence sampler's proposal (independence.hpp).
//
// The Laplace approximation at the least-squares point is a poor proposal when the fit stopped short
// of the mode or the posterior is not Gaussian: independence chains then rarely move and R-hat stays
// far above 1. Before any chain starts, rounds of importance sampling move the proposal onto the
// posterior: each round draws a batch from the current t proposal q, weighs each point by
// w = pi / q (pi: the posterior with the nuisance integrated out where the target offers it) and
// refits q to the weighted mean and covariance. When the weights are too uneven to estimate moments
// (effective sample size below a fraction of the batch), they are tempered, w^beta with beta < 1: the
// moments are then those of the bridge q^(1-beta) pi^beta, a step from q towards pi (the adaptive
// tempering of sequential Monte Carlo: Del Moral, Doucet & Jasra 2006, J. R. Stat. Soc. B 68(3)).
// Rounds stop once a round at beta = 1 keeps the target effective sample size.
#include <vector>

#include <Eigen/Dense>

#include "bayes/target.hpp"
#include "core/rng.hpp"

namespace terracal::bayes {

struct ProposalAdaptationOptions {
  int points = 256;            // draws per round (one batch of forward runs)
  int max_rounds = 12;         // rounds at most
  double min_ess_fraction = 0.2;  // tempering keeps the weights' ESS at this fraction of `points`
  // Rounds at beta = 1 continue until the weights' ESS over all rounds' points reaches this (0: the
  // first round at beta = 1 ends): a covariance fitted to few effective points is a noisy proposal.
  double final_ess = 0;
  double df = 4.0;             // the t proposal's degrees of freedom
  double scale = 1.3;          // proposal covariance = scale^2 * the fitted covariance
};

struct AdaptedProposal {
  Eigen::VectorXd mean;
  Eigen::MatrixXd covariance;  // the fitted covariance (before `scale`)
  int rounds = 0;
  double beta = 0;  // the last round's tempering exponent (1: the posterior's own weights)
  double ess = 0;   // the last round's effective sample size at beta
  long evaluations = 0;
  bool reached_posterior = false;  // a round at beta = 1 kept the target ESS
};

// Starts from (mean, covariance); `nuisance` conditions the density where the target has no
// log_marginal_batch. Throws std::invalid_argument for sizes that do not match or a covariance that
// is not positive definite. A round whose points all fail keeps the proposal as it was and ends.
AdaptedProposal adapt_proposal(const Target& target, const Eigen::VectorXd& mean, const Eigen::MatrixXd& covariance,
                               const Eigen::VectorXd& nuisance, const ProposalAdaptationOptions& opt, Rng& rng);

// The exponent beta in [0, 1] at which weights exp(beta * log_w) keep an effective sample size of at
// least `ess` (1 when the untempered weights do); log_w entries of -inf count as zero weight.
double tempering_exponent(const std::vector<double>& log_w, double ess);
// (sum w)^2 / sum w^2 for w = exp(beta * log_w).
double effective_sample_size(const std::vector<double>& log_w, double beta);

}  // namespace terracal::bayes
