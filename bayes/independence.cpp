#include "bayes/independence.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "bayes/json_state.hpp"
#include "bayes/safe_eval.hpp"

namespace terracal::bayes {

IndependenceSampler::IndependenceSampler(const Target& target, const IndependenceOptions& opt,
                                         const Eigen::VectorXd& mean, const Eigen::MatrixXd& covariance,
                                         std::vector<Eigen::VectorXd> starts, std::vector<Eigen::VectorXd> nuisances,
                                         Rng rng)
    : target_(&target), opt_(opt), x_(std::move(starts)), nuisance_(std::move(nuisances)), rng_(std::move(rng)) {
  check_target(target);
  if (!(opt_.df > 0) || !(opt_.scale > 0)) throw std::invalid_argument("IndependenceOptions: df and scale must be > 0");
  if (x_.empty() || nuisance_.size() != x_.size())
    throw std::invalid_argument("IndependenceSampler: one nuisance vector per chain, at least one chain");
  if (mean.size() != target.dim || covariance.rows() != target.dim || covariance.cols() != target.dim)
    throw std::invalid_argument("IndependenceSampler: proposal sizes do not match the target");
  set_proposal(mean, covariance);
  if (chol_.size() == 0) throw std::invalid_argument("IndependenceSampler: proposal covariance not positive definite");
  for (std::size_t k = 0; k < x_.size(); ++k) {
    if (x_[k].size() != target.dim || nuisance_[k].size() != target.nuisance_dim)
      throw std::invalid_argument("IndependenceSampler: state or nuisance size does not match the target");
    if (collapsed()) {
      std::vector<double> lm;
      target.log_marginal_batch({x_[k]}, lm);
      if (lm.size() != 1 || !std::isfinite(lm[0]))
        throw std::invalid_argument("IndependenceSampler: the start's log density is not finite");
      logp_.push_back(lm[0]);
    } else {
      logp_.push_back(initial_log_density(target, x_[k], nuisance_[k]));
    }
    logq_.push_back(log_q(x_[k]));
  }
  stats_.resize(x_.size());
}

void IndependenceSampler::set_proposal(const Eigen::VectorXd& mean, const Eigen::MatrixXd& covariance) {
  Eigen::LLT<Eigen::MatrixXd> llt(opt_.scale * opt_.scale * covariance);
  if (llt.info() != Eigen::Success || !mean.allFinite()) return;
  const Eigen::MatrixXd L = llt.matrixL();
  if (!L.allFinite()) return;
  mean_ = mean;
  chol_ = L;
}

double IndependenceSampler::log_q(const Eigen::VectorXd& x) const {
  const Eigen::VectorXd z = chol_.triangularView<Eigen::Lower>().solve(x - mean_);
  return -0.5 * (opt_.df + double(x.size())) * std::log1p(z.squaredNorm() / opt_.df);
}

// mean + L z / sqrt(w), z standard normal, w ~ Gamma(df/2, rate df/2): a multivariate t.
Eigen::VectorXd IndependenceSampler::draw() {
  Eigen::VectorXd z(mean_.size());
  for (Eigen::Index j = 0; j < z.size(); ++j) z[j] = rng_.normal();
  const double w = rng_.gamma(0.5 * opt_.df) / (0.5 * opt_.df);
  return mean_ + chol_ * z / std::sqrt(w);
}

// The log densities the moves accept on, of one proposal per chain, as one batch where the target
// has one; failures counted per chain.
void IndependenceSampler::evaluate(const std::vector<Eigen::VectorXd>& ys, std::vector<double>& lps) {
  const std::size_t n = ys.size();
  lps.assign(n, 0.0);
  if (target_->log_marginal_batch || target_->log_density_batch) {
    try {
      if (collapsed())
        target_->log_marginal_batch(ys, lps);
      else
        target_->log_density_batch(ys, nuisance_, lps);
    } catch (const std::exception&) {
      lps.assign(n, std::numeric_limits<double>::quiet_NaN());
    }
    if (lps.size() != n) throw std::logic_error("Target.log_density_batch: wrong number of results");
    for (std::size_t k = 0; k < n; ++k) lps[k] = checked_log_density(lps[k], stats_[k]);
  } else {
    for (std::size_t k = 0; k < n; ++k) lps[k] = safe_log_density(*target_, ys[k], nuisance_[k], stats_[k]);
  }
}

void IndependenceSampler::step() {
  const std::size_t n = x_.size();
  std::vector<Eigen::VectorXd> ys(n);
  for (auto& y : ys) y = draw();
  std::vector<double> lps(n);
  evaluate(ys, lps);
  std::vector<char> moved(n, 0);
  for (std::size_t k = 0; k < n; ++k) {
    ++stats_[k].iterations;
    const double lq = log_q(ys[k]);
    // pi(y) q(x) / (pi(x) q(y))
    if (!accept(log_density_ratio(lps[k], logp_[k]) + logq_[k] - lq, rng_)) continue;
    x_[k] = std::move(ys[k]);
    logp_[k] = lps[k];
    logq_[k] = lq;
    moved[k] = 1;
  }
  if (opt_.local_moves) {
    // The local move: x + (2.38 / sqrt(d)) L z, symmetric, so the ratio is pi(y) / pi(x).
    const double step = 2.38 / std::sqrt(double(mean_.size())) / opt_.scale;
    for (std::size_t k = 0; k < n; ++k) {
      Eigen::VectorXd z(mean_.size());
      for (Eigen::Index j = 0; j < z.size(); ++j) z[j] = rng_.normal();
      ys[k] = x_[k] + step * (chol_ * z);
    }
    evaluate(ys, lps);
    for (std::size_t k = 0; k < n; ++k) {
      if (!accept(log_density_ratio(lps[k], logp_[k]), rng_)) continue;
      x_[k] = std::move(ys[k]);
      logp_[k] = lps[k];
      logq_[k] = log_q(x_[k]);
      moved[k] = 1;
    }
  }
  for (std::size_t k = 0; k < n; ++k) stats_[k].accepted += moved[k];
  if (target_->nuisance_dim > 0)
    for (std::size_t k = 0; k < n; ++k) {
      target_->gibbs(x_[k], nuisance_[k], rng_);
      if (!collapsed()) logp_[k] = safe_log_density(*target_, x_[k], nuisance_[k], stats_[k]);
    }
}

double IndependenceSampler::log_density(std::size_t k) const {
  return collapsed() ? target_->log_density(x_[k], nuisance_[k]) : logp_[k];
}

void IndependenceSampler::refit(const std::vector<Eigen::VectorXd>& draws) {
  const Eigen::Index d = mean_.size();
  if (static_cast<Eigen::Index>(draws.size()) < 4 * d) return;
  Eigen::VectorXd m = Eigen::VectorXd::Zero(d);
  for (const auto& x : draws) m += x;
  m /= double(draws.size());
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(d, d);
  for (const auto& x : draws) c += (x - m) * (x - m).transpose();
  c /= double(draws.size() - 1);
  const Eigen::VectorXd old_mean = mean_;
  const Eigen::MatrixXd old_chol = chol_;
  set_proposal(m, c);
  if (mean_ == old_mean && chol_ == old_chol) return;  // not positive definite: kept
  for (std::size_t k = 0; k < x_.size(); ++k) logq_[k] = log_q(x_[k]);
}

nlohmann::json IndependenceSampler::save() const {
  nlohmann::json logp = nlohmann::json::array(), logq = nlohmann::json::array(), stats = nlohmann::json::array();
  for (double v : logp_) logp.push_back(encode_double(v));
  for (double v : logq_) logq.push_back(encode_double(v));
  for (const auto& s : stats_) stats.push_back(stats_to_json(s));
  return {{"sampler", "independence"},
          {"mean", vector_to_json(mean_)},
          {"chol", matrix_to_json(chol_)},
          {"states", vectors_to_json(x_)},
          {"nuisances", vectors_to_json(nuisance_)},
          {"log_densities", logp},
          {"log_proposals", logq},
          {"rng", rng_.state()},
          {"stats", stats}};
}

void IndependenceSampler::load(const nlohmann::json& j) {
  if (j.at("sampler") != "independence")
    throw std::invalid_argument("IndependenceSampler::load: not an independence-sampler checkpoint");
  const std::size_t k = x_.size();
  const Eigen::Index d = mean_.size();
  auto mean = vector_from_json(j.at("mean"), d);
  auto chol = matrix_from_json(j.at("chol"), d, d);
  auto states = vectors_from_json(j.at("states"), k, d);
  auto nuisances = vectors_from_json(j.at("nuisances"), k, target_->nuisance_dim);
  const auto &jp = j.at("log_densities"), &jq = j.at("log_proposals"), &js = j.at("stats");
  if (jp.size() != k || jq.size() != k || js.size() != k)
    throw std::invalid_argument("IndependenceSampler::load: wrong chain count");
  std::vector<double> logp, logq;
  std::vector<ChainStats> stats;
  for (std::size_t i = 0; i < k; ++i) {
    logp.push_back(decode_double(jp[i]));
    logq.push_back(decode_double(jq[i]));
    stats.push_back(stats_from_json(js[i]));
  }
  Rng rng = rng_;
  rng.set_state(j.at("rng").get<std::string>());
  mean_ = std::move(mean);
  chol_ = std::move(chol);
  x_ = std::move(states);
  nuisance_ = std::move(nuisances);
  logp_ = std::move(logp);
  logq_ = std::move(logq);
  stats_ = std::move(stats);
  rng_ = std::move(rng);
}

}  // namespace terracal::bayes
