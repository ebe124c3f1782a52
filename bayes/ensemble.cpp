#include "bayes/ensemble.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "bayes/json_state.hpp"
#include "bayes/safe_eval.hpp"

namespace terracal::bayes {
namespace {

void check_walkers(const Target& target, const EnsembleOptions& opt, const std::vector<Eigen::VectorXd>& walkers,
                   std::vector<Eigen::VectorXd>& nuisances) {
  check_target(target);
  if (!(opt.a > 1.0)) throw std::invalid_argument("EnsembleOptions: a must be > 1");
  const std::size_t k = walkers.size();
  if (k % 2 != 0 || k < 2 * std::size_t(target.dim))
    throw std::invalid_argument("EnsembleSampler: needs an even number of walkers, at least 2*dim");
  if (nuisances.empty() && target.nuisance_dim == 0) nuisances.assign(k, Eigen::VectorXd());
  if (nuisances.size() != k) throw std::invalid_argument("EnsembleSampler: one nuisance vector per walker");
  for (std::size_t i = 0; i < k; ++i)
    if (walkers[i].size() != target.dim || nuisances[i].size() != target.nuisance_dim)
      throw std::invalid_argument("EnsembleSampler: walker or nuisance size does not match the target");
}

// z with density g(z) ∝ 1/sqrt(z) on [1/a, a] by inversion; g(1/z) = z g(z) makes the move
// symmetric in the sense Goodman & Weare need.
double stretch_factor(double a, Rng& rng) {
  const double s = (a - 1.0) * rng.uniform() + 1.0;
  return s * s / a;
}

}  // namespace

EnsembleSampler::EnsembleSampler(const Target& target, const EnsembleOptions& opt, std::vector<Eigen::VectorXd> walkers,
                                 std::vector<Eigen::VectorXd> nuisances, Rng rng)
    : target_(&target),
      opt_(opt),
      walkers_(std::move(walkers)),
      nuisances_(std::move(nuisances)),
      rng_(std::move(rng)) {
  check_walkers(target, opt_, walkers_, nuisances_);
  for (std::size_t k = 0; k < walkers_.size(); ++k)
    logp_.push_back(initial_log_density(target, walkers_[k], nuisances_[k]));
  stats_.resize(walkers_.size());
}

void EnsembleSampler::step() {
  const std::size_t half = walkers_.size() / 2;
  move_half(0, half);
  move_half(half, 0);
  if (target_->nuisance_dim > 0)
    for (std::size_t k = 0; k < walkers_.size(); ++k) gibbs_update(k);
}

void EnsembleSampler::move_half(std::size_t first, std::size_t other_first) {
  const std::size_t half = walkers_.size() / 2;
  if (target_->log_density_batch) return move_half_batched(first, other_first);
  for (std::size_t k = first; k < first + half; ++k) stretch_move(k, other_first);
}

// The same stretch moves, but every proposal of the half drawn first and evaluated as one batch.
// (The random numbers come in another order than stretch_move's, so the draws differ from the
// one-by-one path's for the same seed; each path is reproducible on its own.)
void EnsembleSampler::move_half_batched(std::size_t first, std::size_t other_first) {
  const std::size_t half = walkers_.size() / 2;
  std::vector<Eigen::VectorXd> ys(half), nus(half);
  std::vector<double> zs(half), lps(half);
  for (std::size_t i = 0; i < half; ++i) {
    const std::size_t k = first + i, j = other_first + rng_.below(half);
    zs[i] = stretch_factor(opt_.a, rng_);
    ys[i] = walkers_[j] + zs[i] * (walkers_[k] - walkers_[j]);
    nus[i] = nuisances_[k];
  }
  try {
    target_->log_density_batch(ys, nus, lps);
  } catch (const std::exception&) {
    lps.assign(half, std::numeric_limits<double>::quiet_NaN());
  }
  if (lps.size() != half) throw std::logic_error("Target.log_density_batch: wrong number of results");
  for (std::size_t i = 0; i < half; ++i) {
    const std::size_t k = first + i;
    const double lp = checked_log_density(lps[i], stats_[k]);
    ++stats_[k].iterations;
    if (!accept((target_->dim - 1) * std::log(zs[i]) + log_density_ratio(lp, logp_[k]), rng_)) continue;
    walkers_[k] = std::move(ys[i]);
    logp_[k] = lp;
    ++stats_[k].accepted;
  }
}

// y = x_j + z (x_k - x_j) with x_j from the other half, accepted with min(1, z^(d-1) pi(y)/pi(x_k))
// (Goodman & Weare 2010, eq. 7). The other half does not change during this half's moves, so
// moving in place equals moving all walkers of the half at once.
void EnsembleSampler::stretch_move(std::size_t k, std::size_t other_first) {
  const std::size_t j = other_first + rng_.below(walkers_.size() / 2);
  const double z = stretch_factor(opt_.a, rng_);
  Eigen::VectorXd y = walkers_[j] + z * (walkers_[k] - walkers_[j]);
  const double lp = safe_log_density(*target_, y, nuisances_[k], stats_[k]);
  ++stats_[k].iterations;
  if (!accept((target_->dim - 1) * std::log(z) + log_density_ratio(lp, logp_[k]), rng_)) return;
  walkers_[k] = std::move(y);
  logp_[k] = lp;
  ++stats_[k].accepted;
}

// Each walker carries its own nuisance, drawn from its exact conditional; its log density
// changes with it and is recomputed (as in DramChain::gibbs_update).
void EnsembleSampler::gibbs_update(std::size_t k) {
  target_->gibbs(walkers_[k], nuisances_[k], rng_);
  logp_[k] = safe_log_density(*target_, walkers_[k], nuisances_[k], stats_[k]);
}

nlohmann::json EnsembleSampler::save() const {
  nlohmann::json logp = nlohmann::json::array(), stats = nlohmann::json::array();
  for (double v : logp_) logp.push_back(encode_double(v));
  for (const auto& s : stats_) stats.push_back(stats_to_json(s));
  return {{"sampler", "ensemble"},
          {"walkers", vectors_to_json(walkers_)},
          {"nuisances", vectors_to_json(nuisances_)},
          {"log_densities", logp},
          {"rng", rng_.state()},
          {"stats", stats}};
}

void EnsembleSampler::load(const nlohmann::json& j) {
  if (j.at("sampler") != "ensemble") throw std::invalid_argument("EnsembleSampler::load: not an ensemble checkpoint");
  const std::size_t k = walkers_.size();
  auto walkers = vectors_from_json(j.at("walkers"), k, target_->dim);
  auto nuisances = vectors_from_json(j.at("nuisances"), k, target_->nuisance_dim);
  const auto& jl = j.at("log_densities");
  const auto& js = j.at("stats");
  if (jl.size() != k || js.size() != k) throw std::invalid_argument("EnsembleSampler::load: wrong walker count");
  std::vector<double> logp;
  std::vector<ChainStats> stats;
  for (std::size_t i = 0; i < k; ++i) {
    logp.push_back(decode_double(jl[i]));
    stats.push_back(stats_from_json(js[i]));
  }
  Rng rng = rng_;
  rng.set_state(j.at("rng").get<std::string>());
  // Everything parsed before anything changes: a bad checkpoint leaves the sampler as it was.
  walkers_ = std::move(walkers);
  nuisances_ = std::move(nuisances);
  logp_ = std::move(logp);
  stats_ = std::move(stats);
  rng_ = std::move(rng);
}

}  // namespace terracal::bayes
