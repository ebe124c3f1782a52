#include "bayes/dram.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "bayes/json_state.hpp"
#include "bayes/safe_eval.hpp"

namespace terracal::bayes {
namespace {

Eigen::VectorXd standard_normal(Eigen::Index n, Rng& rng) {
  Eigen::VectorXd z(n);
  for (Eigen::Index i = 0; i < n; ++i) z[i] = rng.normal();
  return z;
}

std::optional<Eigen::MatrixXd> cholesky(const Eigen::MatrixXd& cov) {
  Eigen::LLT<Eigen::MatrixXd> llt(cov);
  if (llt.info() != Eigen::Success) return std::nullopt;
  return Eigen::MatrixXd(llt.matrixL());
}

// log(1 - exp(a)) for a <= 0, accurate near both ends (Maechler 2012): 1 - alpha underflows to
// 0 in plain arithmetic when the first-stage alpha is within rounding of 1.
double log1m_exp(double a) { return a > -std::numbers::ln2 ? std::log(-std::expm1(a)) : std::log1p(-std::exp(a)); }

// log of the first-stage acceptance probability alpha1(from -> to) = min(1, pi(to) / pi(from)).
double log_alpha1(double lp_to, double lp_from) { return std::min(0.0, log_density_ratio(lp_to, lp_from)); }

DramOptions resolved(DramOptions opt, int dim) {
  if (opt.scale == 0) opt.scale = 2.38 * 2.38 / dim;  // Gelman, Roberts & Gilks (1996)
  if (!(opt.scale > 0) || !(opt.dr_scale > 0) || !(opt.regularisation >= 0) || opt.adapt_start < 0)
    throw std::invalid_argument("DramOptions: scale, dr_scale must be > 0, regularisation, adapt_start >= 0");
  return opt;
}

}  // namespace

DramChain::DramChain(const Target& target, const DramOptions& opt, Eigen::VectorXd x0, Eigen::VectorXd nuisance0,
                     const Eigen::MatrixXd& proposal_covariance, Rng rng)
    : target_(&target),
      opt_(resolved(opt, target.dim)),
      x_(std::move(x0)),
      nuisance_(std::move(nuisance0)),
      adaptation_(target.dim),
      rng_(std::move(rng)) {
  check_target(target);
  if (x_.size() != target.dim || nuisance_.size() != target.nuisance_dim)
    throw std::invalid_argument("DramChain: x0 / nuisance0 size does not match the target");
  if (proposal_covariance.rows() != target.dim || proposal_covariance.cols() != target.dim)
    throw std::invalid_argument("DramChain: proposal covariance is not dim x dim");
  const auto chol = cholesky(proposal_covariance);
  if (!chol) throw std::invalid_argument("DramChain: proposal covariance is not positive definite");
  chol_ = *chol;
  logp_ = initial_log_density(target, x_, nuisance_);
}

void DramChain::step(bool adapt) {
  ++stats_.iterations;
  if (delayed_rejection_move()) ++stats_.accepted;
  if (target_->nuisance_dim > 0) gibbs_update();
  if (adapt) adapt_proposal();
}

void DramChain::move_to(const Eigen::VectorXd& y, double lp) {
  x_ = y;
  logp_ = lp;
}

bool DramChain::delayed_rejection_move() {
  const Eigen::VectorXd z1 = standard_normal(target_->dim, rng_);
  const Eigen::VectorXd y1 = x_ + chol_ * z1;
  const double lp1 = safe_log_density(*target_, y1, nuisance_, stats_);
  if (accept(log_density_ratio(lp1, logp_), rng_)) {
    move_to(y1, lp1);
    return true;
  }
  return second_stage(z1, lp1);
}

// Second stage from x, y1 = x + L z1 rejected, y2 = x + sqrt(dr_scale) L z2. The second-stage
// proposal is a Gaussian centred at x, hence symmetric, and cancels; detailed balance needs
// (Mira 2001; Haario et al. 2006, eq. 2):
//   alpha2 = min(1, pi(y2) q1(y2 -> y1) (1 - alpha1(y2 -> y1)) / (pi(x) q1(x -> y1) (1 - alpha1(x -> y1)))).
// With C1 = L L^T, L^-1 (y1 - y2) = z1 - sqrt(dr_scale) z2, so both q1 terms need no solve.
bool DramChain::second_stage(const Eigen::VectorXd& z1, double lp1) {
  const double root = std::sqrt(opt_.dr_scale);
  const Eigen::VectorXd z2 = standard_normal(target_->dim, rng_);
  const Eigen::VectorXd y2 = x_ + root * (chol_ * z2);
  const double lp2 = safe_log_density(*target_, y2, nuisance_, stats_);
  const double log_q_ratio = -0.5 * (z1 - root * z2).squaredNorm() + 0.5 * z1.squaredNorm();
  // alpha1(x -> y1) < 1 here (stage 1 rejected), so the denominator's log1m_exp is finite.
  const double log_ratio =
      log_density_ratio(lp2, logp_) + log_q_ratio + log1m_exp(log_alpha1(lp1, lp2)) - log1m_exp(log_alpha1(lp1, logp_));
  if (!accept(log_ratio, rng_)) return false;
  move_to(y2, lp2);
  return true;
}

// The log density of x depends on the nuisance: after the nuisance changes, the stored value
// must be recomputed or the next Metropolis ratio would compare densities of two targets.
void DramChain::gibbs_update() {
  target_->gibbs(x_, nuisance_, rng_);
  logp_ = safe_log_density(*target_, x_, nuisance_, stats_);
}

// Haario et al. (2001): C = s_d (Cov(x_0..x_t) + eps I). eps is taken relative to each variance
// rather than one absolute value, so the regularisation stays negligible for a parameter whose
// variance is 1e-10 of another's. A coordinate that has not moved yet has variance 0, the
// factorisation fails, and the previous proposal is kept (no collapse onto a subspace).
void DramChain::adapt_proposal() {
  adaptation_.add(x_);
  if (adaptation_.count() < std::max<long>(opt_.adapt_start, 2)) return;
  Eigen::MatrixXd cov = adaptation_.covariance();
  cov.diagonal() *= 1.0 + opt_.regularisation;
  if (const auto chol = cholesky(opt_.scale * cov)) chol_ = *chol;
}

nlohmann::json DramChain::save() const {
  return {{"sampler", "dram"},
          {"x", vector_to_json(x_)},
          {"nuisance", vector_to_json(nuisance_)},
          {"log_density", encode_double(logp_)},
          {"rng", rng_.state()},
          {"proposal_cholesky", matrix_to_json(chol_)},
          {"adaptation",
           {{"count", adaptation_.count()},
            {"mean", vector_to_json(adaptation_.mean())},
            {"scatter", matrix_to_json(adaptation_.scatter())}}},
          {"stats", stats_to_json(stats_)}};
}

void DramChain::load(const nlohmann::json& j) {
  if (j.at("sampler") != "dram") throw std::invalid_argument("DramChain::load: not a DRAM checkpoint");
  const int d = target_->dim;
  Eigen::VectorXd x = vector_from_json(j.at("x"), d);
  Eigen::VectorXd nuisance = vector_from_json(j.at("nuisance"), target_->nuisance_dim);
  Eigen::MatrixXd chol = matrix_from_json(j.at("proposal_cholesky"), d, d);
  const auto& a = j.at("adaptation");
  Eigen::VectorXd mean = vector_from_json(a.at("mean"), d);
  Eigen::MatrixXd scatter = matrix_from_json(a.at("scatter"), d, d);
  const double logp = decode_double(j.at("log_density"));
  const ChainStats stats = stats_from_json(j.at("stats"));
  const long count = a.at("count").get<long>();
  Rng rng = rng_;
  rng.set_state(j.at("rng").get<std::string>());
  // Everything parsed before anything changes: a bad checkpoint leaves the chain as it was.
  x_ = std::move(x);
  nuisance_ = std::move(nuisance);
  logp_ = logp;
  chol_ = std::move(chol);
  adaptation_.restore(count, std::move(mean), std::move(scatter));
  rng_ = std::move(rng);
  stats_ = stats;
}

}  // namespace terracal::bayes
