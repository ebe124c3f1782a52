#pragma once
// Independence Metropolis-Hastings with a multivariate-t proposal (Tierney 1994, "Markov chains
// for exploring posterior distributions", Ann. Statist. 22(4)), for targets whose every evaluation
// is a simulation. The proposal does not depend on the chain's state, so one step of many chains is
// one batch of forward runs (Target::log_density_batch: threads, or one GPU launch), and a
// proposal close to the posterior gives nearly independent draws: few runs per effective draw.
//
// Where the target integrates its nuisance out (Target::log_marginal_batch), the moves accept on that
// marginal density and the nuisance is then drawn from its conditional: an exact sampler of the joint
// (p(x, n) = p(x) p(n | x)) whose x-moves do not depend on the nuisance's current draw, which with few
// effective observations per channel varies by factors and would otherwise narrow the acceptance.
//
// The proposal starts as the Laplace approximation (MAP, least-squares covariance) or the one
// adapted by importance sampling (proposal_adaptation.hpp); `refit` fits it to pooled draws (mean
// and covariance), which the calibrator does during warm-up only where adaptation fell short. It is
// fixed while draws are kept, so the kept chains are plain Metropolis-Hastings chains with an exact target. The
// t's heavy tails (df 4) and a covariance inflated by `scale`^2 keep the ratio pi/q bounded where the
// Gaussian approximation is too narrow.
#include <vector>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include "bayes/target.hpp"
#include "core/rng.hpp"

namespace terracal::bayes {

struct IndependenceOptions {
  double df = 4.0;     // degrees of freedom of the t proposal
  double scale = 1.3;  // proposal covariance = scale^2 * the fitted covariance
  // After each independence move, a random-walk move x + (2.38 / sqrt(d)) L z with L the fitted
  // covariance's Cholesky factor (a second batch of runs): a chain that the independence move leaves
  // stuck where the posterior outweighs the proposal (its tails, a curved ridge) still moves.
  bool local_moves = false;
  // Points per chain and step: 1, Metropolis-Hastings (one run per chain); more, i-SIR, the next
  // state drawn from the current one and tries - 1 proposals by importance weight (one batch of
  // chains x (tries - 1) runs per step).
  int tries = 1;
  // Steps whose fresh proposals are drawn and evaluated as one batch, then served step by step:
  // they do not depend on the chains' states, so a GPU that holds several steps' runs in one launch
  // runs them in about the time of one step's. The chains are the same Markov chains (a step's
  // proposals are drawn before it, from the proposal it uses); only the random numbers' order
  // differs from 1. Needs a target whose moves do not depend on the chains' nuisance (collapsed,
  // or none). Proposals drawn for steps that are never taken are not counted anywhere.
  int lookahead = 1;
  // Delayed acceptance (Christen & Fox 2005, "Markov chain Monte Carlo using an approximation",
  // J. Comput. Graph. Statist. 14(4)) for the random-walk move (needs local_moves): each move is first
  // tested on a surrogate of the posterior, a t with the proposal's degrees of freedom, mean and
  // covariance before `scale`, and only the moves that pass it are run; the second test on the run's
  // density corrects for the surrogate (ratio pi(y) pit(x) / (pi(x) pit(y))), so the chain's target
  // is exact. Most random-walk moves are rejected, and the surrogate predicts most of those: they
  // cost no run. The independence move is not screened: its screen (pit(y) q(x) / (pit(x) q(y)))
  // also turned away the moves that take a chain off a point the proposal under-weights, and chains
  // sat there for hundreds of steps (docs/decisions.md, "Delayed acceptance").
  bool delayed_acceptance = false;
};

class IndependenceSampler {
 public:
  // `target` must outlive the sampler. Throws std::invalid_argument for sizes that do not match,
  // a covariance that is not positive definite, or a start whose log density is not finite.
  IndependenceSampler(const Target& target, const IndependenceOptions& opt, const Eigen::VectorXd& mean,
                      const Eigen::MatrixXd& covariance, std::vector<Eigen::VectorXd> starts,
                      std::vector<Eigen::VectorXd> nuisances, Rng rng);
  // One independence move for every chain (all proposals evaluated as one batch: Metropolis-Hastings
  // or, with tries > 1, i-SIR), then the Gibbs update of every chain's nuisance.
  void step();
  // Refits the proposal to the given draws (rows: points); kept as is when they are too few or
  // their covariance is not positive definite.
  void refit(const std::vector<Eigen::VectorXd>& draws);
  const std::vector<Eigen::VectorXd>& states() const { return x_; }
  const std::vector<Eigen::VectorXd>& nuisances() const { return nuisance_; }
  // The log density the moves accept on: the marginal where the target is collapsed, else the
  // density given the chain's nuisance.
  const std::vector<double>& log_densities() const { return logp_; }
  // Chain k's log density given its nuisance (a cached run for simulation-backed targets).
  double log_density(std::size_t k) const;
  bool collapsed() const { return static_cast<bool>(target_->log_marginal_batch); }
  const std::vector<ChainStats>& stats() const { return stats_; }
  std::size_t size() const { return x_.size(); }
  nlohmann::json save() const;
  void load(const nlohmann::json& j);

 private:
  void set_proposal(const Eigen::VectorXd& mean, const Eigen::MatrixXd& covariance);
  double log_q(const Eigen::VectorXd& x) const;          // the proposal's log density, up to a constant
  double log_surrogate(const Eigen::VectorXd& x) const;  // delayed acceptance's t, up to a constant
  void evaluate(const std::vector<Eigen::VectorXd>& ys, std::size_t per, std::vector<double>& lps);
  void evaluate_raw(const std::vector<Eigen::VectorXd>& ys, std::size_t per, std::vector<double>& lps) const;
  void evaluate_raw(const std::vector<Eigen::VectorXd>& ys, const std::vector<std::size_t>& chain_of,
                    std::vector<double>& lps) const;
  std::vector<char> delayed_move(std::vector<Eigen::VectorXd>& ys);
  void next_proposals(std::size_t per, std::vector<Eigen::VectorXd>& ys, std::vector<double>& lps);
  std::vector<char> metropolis_move();
  std::vector<char> local_move();
  void move_to(std::size_t k, Eigen::VectorXd y, double lp, double lq);
  std::vector<char> resample_move();
  Eigen::VectorXd draw();

  const Target* target_;
  IndependenceOptions opt_;
  Eigen::VectorXd mean_;
  Eigen::MatrixXd chol_;  // lower Cholesky factor of the proposal covariance (scale included)
  std::vector<Eigen::VectorXd> x_, nuisance_;
  std::vector<double> logp_, logq_;
  std::vector<ChainStats> stats_;
  Rng rng_;
  // Proposals drawn ahead (lookahead > 1) and their log densities as the target returned them; the
  // next step's block starts at ahead_next_.
  std::vector<Eigen::VectorXd> ahead_ys_;
  std::vector<double> ahead_lps_;
  std::size_t ahead_next_ = 0;
};

}  // namespace terracal::bayes
