#include "bayes/independence.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
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
  if (opt_.tries < 1) throw std::invalid_argument("IndependenceOptions: tries must be >= 1");
  if (opt_.lookahead < 1) throw std::invalid_argument("IndependenceOptions: lookahead must be >= 1");
  if (opt_.delayed_acceptance && !opt_.local_moves)
    throw std::invalid_argument(
        "IndependenceOptions: delayed acceptance screens the random-walk move: needs local_moves");
  if (opt_.lookahead > 1 && target.nuisance_dim > 0 && !target.log_marginal_batch)
    throw std::invalid_argument(
        "IndependenceOptions: lookahead > 1 needs a target whose moves do not depend on the nuisance (collapsed)");
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

// A t with the proposal's degrees of freedom, mean and covariance before `scale` (chol_ / scale is
// its Cholesky factor): narrower than the proposal, so it screens, and with polynomial tails, so
// pi / pit stays bounded where the posterior is heavier-tailed than a Gaussian (with a Gaussian
// surrogate a chain that reached such a tail sat there: the second stage's pit(x) / pi(x) is tiny).
double IndependenceSampler::log_surrogate(const Eigen::VectorXd& x) const {
  const Eigen::VectorXd z = chol_.triangularView<Eigen::Lower>().solve(x - mean_);
  return -0.5 * (opt_.df + double(x.size())) * std::log1p(opt_.scale * opt_.scale * z.squaredNorm() / opt_.df);
}

// mean + L z / sqrt(w), z standard normal, w ~ Gamma(df/2, rate df/2): a multivariate t.
Eigen::VectorXd IndependenceSampler::draw() {
  Eigen::VectorXd z(mean_.size());
  for (Eigen::Index j = 0; j < z.size(); ++j) z[j] = rng_.normal();
  const double w = rng_.gamma(0.5 * opt_.df) / (0.5 * opt_.df);
  return mean_ + chol_ * z / std::sqrt(w);
}

// The log densities the moves accept on, of `per` proposals per chain (chain k's are ys[k per ..
// (k + 1) per)), as one batch where the target has one; failures counted per chain.
void IndependenceSampler::evaluate(const std::vector<Eigen::VectorXd>& ys, std::size_t per, std::vector<double>& lps) {
  evaluate_raw(ys, per, lps);
  for (std::size_t i = 0; i < ys.size(); ++i) lps[i] = checked_log_density(lps[i], stats_[i / per]);
}

// The same before the failure conventions (NaN where a run failed or the batch threw). Points
// past the chains' first block (drawn ahead) belong to chain (i / per) mod chains.
void IndependenceSampler::evaluate_raw(const std::vector<Eigen::VectorXd>& ys, std::size_t per,
                                       std::vector<double>& lps) const {
  std::vector<std::size_t> chain_of(ys.size());
  for (std::size_t i = 0; i < ys.size(); ++i) chain_of[i] = (i / per) % x_.size();
  evaluate_raw(ys, chain_of, lps);
}

// The same for points of any chains: ys[i] is evaluated with chain chain_of[i]'s nuisance.
void IndependenceSampler::evaluate_raw(const std::vector<Eigen::VectorXd>& ys, const std::vector<std::size_t>& chain_of,
                                       std::vector<double>& lps) const {
  const std::size_t n = ys.size();
  lps.assign(n, 0.0);
  const auto nuisance_of = [&](std::size_t i) -> const Eigen::VectorXd& { return nuisance_[chain_of[i]]; };
  if (target_->log_marginal_batch || target_->log_density_batch) {
    try {
      if (collapsed()) {
        target_->log_marginal_batch(ys, lps);
      } else {
        std::vector<Eigen::VectorXd> nv;
        for (std::size_t i = 0; i < n; ++i) nv.push_back(nuisance_of(i));
        target_->log_density_batch(ys, nv, lps);
      }
    } catch (const std::exception&) {
      lps.assign(n, std::numeric_limits<double>::quiet_NaN());
    }
    if (lps.size() != n) throw std::logic_error("Target.log_density_batch: wrong number of results");
  } else {
    for (std::size_t i = 0; i < n; ++i) lps[i] = raw_log_density(*target_, ys[i], nuisance_of(i));
  }
}

// This step's `per` fresh proposals per chain and their log densities (failures counted now, for
// the step that uses them). With lookahead > 1 the next `lookahead` steps' proposals are drawn and
// evaluated as one batch when the last batch is used up.
void IndependenceSampler::next_proposals(std::size_t per, std::vector<Eigen::VectorXd>& ys, std::vector<double>& lps) {
  const std::size_t block = x_.size() * per;
  if (ahead_next_ + block > ahead_ys_.size()) {
    ahead_ys_.resize(block * static_cast<std::size_t>(opt_.lookahead));
    for (auto& y : ahead_ys_) y = draw();
    evaluate_raw(ahead_ys_, per, ahead_lps_);
    ahead_next_ = 0;
  }
  const auto from = static_cast<std::ptrdiff_t>(ahead_next_), to = from + static_cast<std::ptrdiff_t>(block);
  ys.assign(std::make_move_iterator(ahead_ys_.begin() + from), std::make_move_iterator(ahead_ys_.begin() + to));
  lps.assign(ahead_lps_.begin() + from, ahead_lps_.begin() + to);
  ahead_next_ += block;
  if (ahead_next_ == ahead_ys_.size()) {
    ahead_ys_.clear();
    ahead_lps_.clear();
    ahead_next_ = 0;
  }
  for (std::size_t i = 0; i < block; ++i) lps[i] = checked_log_density(lps[i], stats_[i / per]);
}

// Chain k takes the accepted point y, with its log density and its proposal log density.
void IndependenceSampler::move_to(std::size_t k, Eigen::VectorXd y, double lp, double lq) {
  x_[k] = std::move(y);
  logp_[k] = lp;
  logq_[k] = lq;
}

// Metropolis-Hastings with the independence proposal: one run per chain.
std::vector<char> IndependenceSampler::metropolis_move() {
  const std::size_t n = x_.size();
  std::vector<Eigen::VectorXd> ys;
  std::vector<double> lps;
  next_proposals(1, ys, lps);
  std::vector<char> moved(n, 0);
  for (std::size_t k = 0; k < n; ++k) {
    const double lq = log_q(ys[k]);
    // pi(y) q(x) / (pi(x) q(y))
    if (!accept(log_density_ratio(lps[k], logp_[k]) + logq_[k] - lq, rng_)) continue;
    move_to(k, std::move(ys[k]), lps[k], lq);
    moved[k] = 1;
  }
  return moved;
}

// Delayed acceptance's two stages for one random-walk proposal per chain: the first accepts on the
// surrogate, pit(y) / pit(x) (the move is symmetric), and the proposals that pass it are run as one
// batch; the second accepts on pi(y) pit(x) / (pi(x) pit(y)), which makes the two-stage kernel
// reversible with respect to pi whatever the surrogate (Christen & Fox 2005).
std::vector<char> IndependenceSampler::delayed_move(std::vector<Eigen::VectorXd>& ys) {
  const std::size_t n = x_.size();
  std::vector<double> surrogate(n);
  std::vector<std::size_t> passed;
  std::vector<Eigen::VectorXd> run;
  for (std::size_t k = 0; k < n; ++k) {
    surrogate[k] = log_surrogate(ys[k]) - log_surrogate(x_[k]);
    if (!accept(surrogate[k], rng_)) continue;
    passed.push_back(k);
    run.push_back(ys[k]);
  }
  std::vector<char> moved(n, 0);
  if (passed.empty()) return moved;
  std::vector<double> lps;
  evaluate_raw(run, passed, lps);
  for (std::size_t i = 0; i < passed.size(); ++i) {
    const std::size_t k = passed[i];
    const double lp = checked_log_density(lps[i], stats_[k]);
    if (!accept(log_density_ratio(lp, logp_[k]) - surrogate[k], rng_)) continue;
    const double lq = log_q(ys[k]);  // before ys[k] is moved from
    move_to(k, std::move(ys[k]), lp, lq);
    moved[k] = 1;
  }
  return moved;
}

// Iterated sampling importance resampling (i-SIR; Andrieu, Lee & Vihola 2018, "Uniform ergodicity of
// the iterated conditional SMC and geometric ergodicity of particle Gibbs samplers", Bernoulli 24(2)):
// the chain's state and tries - 1 fresh proposals form a set, and the next state is drawn from it with
// probability proportional to the importance weight pi / q. The kernel leaves pi invariant for any
// number of tries; the more tries, the less likely the chain stays, so many chains' tries fill one
// large batch and the chains need few sequential steps (a GPU runs a large batch in about the time of
// a small one). A failed run has no weight.
std::vector<char> IndependenceSampler::resample_move() {
  const std::size_t n = x_.size(), fresh = static_cast<std::size_t>(opt_.tries - 1);
  std::vector<Eigen::VectorXd> ys;
  std::vector<double> lps;
  next_proposals(fresh, ys, lps);
  std::vector<char> moved(n, 0);
  std::vector<double> log_w(fresh + 1), lq(fresh);
  for (std::size_t k = 0; k < n; ++k) {
    log_w[0] = logp_[k] - logq_[k];
    double top = log_w[0];
    for (std::size_t j = 0; j < fresh; ++j) {
      lq[j] = log_q(ys[k * fresh + j]);
      const double lp = lps[k * fresh + j];
      log_w[j + 1] = lp == kMinusInf ? kMinusInf : lp - lq[j];
      top = std::max(top, log_w[j + 1]);
    }
    double total = 0;
    for (double& w : log_w) total += (w = std::exp(w - top));
    double u = rng_.uniform() * total;
    std::size_t pick = 0;
    while (pick < fresh && u >= log_w[pick]) u -= log_w[pick++];
    if (pick == 0 || log_w[pick] == 0) continue;  // the state stays (a zero weight is never picked)
    x_[k] = std::move(ys[k * fresh + pick - 1]);
    logp_[k] = lps[k * fresh + pick - 1];
    logq_[k] = lq[pick - 1];
    moved[k] = 1;
  }
  return moved;
}

// The random-walk move x + (2.38 / sqrt(d)) L z, with L the fitted covariance's Cholesky factor:
// symmetric, so the ratio is pi(y) / pi(x); with delayed acceptance pit(y) / pit(x) first, and only
// the moves that pass it run.
std::vector<char> IndependenceSampler::local_move() {
  const std::size_t n = x_.size();
  const double step = 2.38 / std::sqrt(double(mean_.size())) / opt_.scale;
  std::vector<Eigen::VectorXd> ys(n);
  for (std::size_t k = 0; k < n; ++k) {
    Eigen::VectorXd z(mean_.size());
    for (Eigen::Index j = 0; j < z.size(); ++j) z[j] = rng_.normal();
    ys[k] = x_[k] + step * (chol_ * z);
  }
  if (opt_.delayed_acceptance) return delayed_move(ys);
  std::vector<double> lps;
  evaluate(ys, 1, lps);
  std::vector<char> moved(n, 0);
  for (std::size_t k = 0; k < n; ++k) {
    if (!accept(log_density_ratio(lps[k], logp_[k]), rng_)) continue;
    const double lq = log_q(ys[k]);  // before ys[k] is moved from
    move_to(k, std::move(ys[k]), lps[k], lq);
    moved[k] = 1;
  }
  return moved;
}

void IndependenceSampler::step() {
  const std::size_t n = x_.size();
  for (auto& s : stats_) ++s.iterations;
  std::vector<char> moved = opt_.tries > 1 ? resample_move() : metropolis_move();
  if (opt_.local_moves) {
    const std::vector<char> local = local_move();
    for (std::size_t k = 0; k < n; ++k) moved[k] = moved[k] || local[k];
  }
  for (std::size_t k = 0; k < n; ++k) stats_[k].accepted += moved[k];
  if (target_->nuisance_dim > 0 && collapsed()) {
    // The states as one batch first: a simulation-backed target then serves the Gibbs updates, which
    // need each state's residuals, from its cache, instead of running the states it evicted one by one.
    std::vector<double> ignored;
    try {
      target_->log_marginal_batch(x_, ignored);
    } catch (const std::exception&) {
    }
  }
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
  // Proposals drawn ahead came from the old proposal: weighed by the new one they would be wrong.
  ahead_ys_.clear();
  ahead_lps_.clear();
  ahead_next_ = 0;
  for (std::size_t k = 0; k < x_.size(); ++k) logq_[k] = log_q(x_[k]);
}

nlohmann::json IndependenceSampler::save() const {
  nlohmann::json logp = nlohmann::json::array(), logq = nlohmann::json::array(), stats = nlohmann::json::array();
  for (double v : logp_) logp.push_back(encode_double(v));
  for (double v : logq_) logq.push_back(encode_double(v));
  for (const auto& s : stats_) stats.push_back(stats_to_json(s));
  // The proposals drawn ahead and not yet used, so that a resumed run takes the same steps.
  nlohmann::json ahead_lps = nlohmann::json::array();
  const std::vector<Eigen::VectorXd> ahead(ahead_ys_.begin() + static_cast<std::ptrdiff_t>(ahead_next_),
                                           ahead_ys_.end());
  for (std::size_t i = ahead_next_; i < ahead_lps_.size(); ++i) ahead_lps.push_back(encode_double(ahead_lps_[i]));
  return {{"sampler", "independence"},
          {"ahead", vectors_to_json(ahead)},
          {"ahead_log_densities", ahead_lps},
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
  std::vector<double> logp, logq, ahead_lps;
  std::vector<ChainStats> stats;
  for (std::size_t i = 0; i < k; ++i) {
    logp.push_back(decode_double(jp[i]));
    logq.push_back(decode_double(jq[i]));
    stats.push_back(stats_from_json(js[i]));
  }
  // Checkpoints written before proposals were drawn ahead have none.
  std::vector<Eigen::VectorXd> ahead;
  if (j.contains("ahead")) {
    const auto& ja = j.at("ahead");
    const auto& jl = j.at("ahead_log_densities");
    if (!ja.is_array() || !jl.is_array() || ja.size() != jl.size() || ja.size() % k != 0)
      throw std::invalid_argument("IndependenceSampler::load: proposals drawn ahead do not fit the chains");
    ahead = vectors_from_json(ja, ja.size(), d);
    for (const auto& v : jl) ahead_lps.push_back(decode_double(v));
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
  ahead_ys_ = std::move(ahead);
  ahead_lps_ = std::move(ahead_lps);
  ahead_next_ = 0;
}

}  // namespace terracal::bayes
