#pragma once
// What DRAM and the ensemble sampler share about evaluating a Target and accepting a move.
// A failed evaluation (NaN, +inf, exception) is mapped to -inf: the proposal is rejected exactly
// as one outside the support, so the chain samples the target truncated to where the forward
// model works, instead of aborting a long run because of one bad parameter vector.
#include <cmath>
#include <exception>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>

#include "bayes/target.hpp"
#include "core/rng.hpp"

namespace terracal::bayes {

inline constexpr double kMinusInf = -std::numeric_limits<double>::infinity();

// The failure conventions of safe_log_density for one value of a batch.
inline double checked_log_density(double lp, ChainStats& stats) {
  if (std::isnan(lp) || lp == std::numeric_limits<double>::infinity()) {
    ++stats.failed_evaluations;
    return kMinusInf;
  }
  return lp;
}

// log density as the target gives it, NaN where it throws (the failure conventions not yet applied:
// samplers that count a failure later, when a move uses the value, call this).
inline double raw_log_density(const Target& target, const Eigen::VectorXd& x, const Eigen::VectorXd& nuisance) {
  try {
    return target.log_density(x, nuisance);
  } catch (const std::exception&) {
    return std::numeric_limits<double>::quiet_NaN();
  }
}

// log density, or -inf (counted in stats.failed_evaluations) when the evaluation failed.
inline double safe_log_density(const Target& target, const Eigen::VectorXd& x, const Eigen::VectorXd& nuisance,
                               ChainStats& stats) {
  return checked_log_density(raw_log_density(target, x, nuisance), stats);
}

// A starting point must be inside the support: a chain started at -inf has no direction to go.
inline double initial_log_density(const Target& target, const Eigen::VectorXd& x, const Eigen::VectorXd& nuisance) {
  ChainStats ignored;
  const double lp = safe_log_density(target, x, nuisance, ignored);
  if (!std::isfinite(lp)) throw std::invalid_argument("sampler: the log density at the initial point is not finite");
  return lp;
}

// Checks what every sampler needs from a Target before it draws anything.
inline void check_target(const Target& target) {
  if (target.dim < 1) throw std::invalid_argument("sampler: Target.dim must be >= 1");
  if (target.nuisance_dim < 0) throw std::invalid_argument("sampler: Target.nuisance_dim must be >= 0");
  if (!target.log_density) throw std::invalid_argument("sampler: Target.log_density is not set");
  if (target.nuisance_dim > 0 && !target.gibbs) throw std::invalid_argument("sampler: Target.gibbs is not set");
}

// Metropolis test on a log acceptance ratio. -inf - -inf (both points outside) is NaN: the
// comparison is false, so it rejects; a current point at -inf accepts any finite proposal.
inline bool accept(double log_ratio, Rng& rng) { return std::log(rng.uniform()) < log_ratio; }

// log ratio of two log densities with the conventions above: moving to -inf never happens,
// moving away from -inf always does.
inline double log_density_ratio(double lp_to, double lp_from) {
  if (lp_to == kMinusInf) return kMinusInf;
  if (lp_from == kMinusInf) return std::numeric_limits<double>::infinity();
  return lp_to - lp_from;
}

}  // namespace terracal::bayes
