#include "bayes/proposal_adaptation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace terracal::bayes {
namespace {

constexpr double kNegInf = -std::numeric_limits<double>::infinity();

// The log densities of xs: with the nuisance integrated out where the target can, else given
// `nuisance`. Failed points (NaN, +inf) come back as NaN.
std::vector<double> log_densities(const Target& t, const std::vector<Eigen::VectorXd>& xs,
                                  const Eigen::VectorXd& nuisance) {
  std::vector<double> out(xs.size(), std::numeric_limits<double>::quiet_NaN());
  try {
    if (t.log_marginal_batch) {
      t.log_marginal_batch(xs, out);
    } else if (t.log_density_batch) {
      t.log_density_batch(xs, std::vector<Eigen::VectorXd>(xs.size(), nuisance), out);
    } else {
      for (std::size_t i = 0; i < xs.size(); ++i) out[i] = t.log_density(xs[i], nuisance);
    }
  } catch (const std::exception&) {
    out.assign(xs.size(), std::numeric_limits<double>::quiet_NaN());
  }
  if (out.size() != xs.size()) throw std::logic_error("adapt_proposal: the target returned the wrong number of results");
  return out;
}

}  // namespace

double effective_sample_size(const std::vector<double>& log_w, double beta) {
  double top = kNegInf;
  for (double v : log_w) top = std::max(top, v);
  if (!std::isfinite(top)) return 0;
  double s = 0, s2 = 0;
  for (double v : log_w) {
    if (!std::isfinite(v)) continue;
    const double w = std::exp(beta * (v - top));
    s += w;
    s2 += w * w;
  }
  return s2 > 0 ? s * s / s2 : 0;
}

double tempering_exponent(const std::vector<double>& log_w, double ess) {
  if (effective_sample_size(log_w, 1.0) >= ess) return 1.0;
  double lo = 0, hi = 1;  // the ESS falls as beta grows: bisect for the largest beta that keeps it
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (effective_sample_size(log_w, mid) >= ess ? lo : hi) = mid;
  }
  return lo;
}

namespace {

// A multivariate t's normalised log density (mean, lower Cholesky factor L of its scale matrix).
struct TDensity {
  Eigen::VectorXd mean;
  Eigen::MatrixXd L;
  double df = 4;
  double log_norm = 0;  // log Gamma((df+d)/2) - log Gamma(df/2) - d/2 log(df pi) - log det L
  double operator()(const Eigen::VectorXd& x) const {
    const Eigen::VectorXd z = L.triangularView<Eigen::Lower>().solve(x - mean);
    return log_norm - 0.5 * (df + double(x.size())) * std::log1p(z.squaredNorm() / df);
  }
};

TDensity t_density(const Eigen::VectorXd& mean, const Eigen::MatrixXd& L, double df) {
  const double d = double(mean.size());
  double log_det = 0;
  for (Eigen::Index j = 0; j < L.rows(); ++j) log_det += std::log(L(j, j));
  return {mean, L, df, std::lgamma(0.5 * (df + d)) - std::lgamma(0.5 * df) - 0.5 * d * std::log(df * M_PI) - log_det};
}

double log_sum_exp(const std::vector<double>& v) {
  double top = kNegInf;
  for (double x : v) top = std::max(top, x);
  if (!std::isfinite(top)) return top;
  double s = 0;
  for (double x : v) s += std::exp(x - top);
  return top + std::log(s);
}

}  // namespace

// Every round's points are kept and weighed against the mixture of all proposals so far
// (deterministic-mixture weights, Cornuet et al. 2012, "Adaptive multiple importance sampling",
// Scand. J. Stat. 39(4)): each round adds to the sample the moments are fitted to instead of
// replacing it, so the fit steadies as rounds accumulate.
AdaptedProposal adapt_proposal(const Target& target, const Eigen::VectorXd& mean, const Eigen::MatrixXd& covariance,
                               const Eigen::VectorXd& nuisance, const ProposalAdaptationOptions& opt, Rng& rng) {
  const Eigen::Index d = target.dim;
  if (mean.size() != d || covariance.rows() != d || covariance.cols() != d)
    throw std::invalid_argument("adapt_proposal: proposal sizes do not match the target");
  if (opt.points < 2 * d + 2 || opt.max_rounds < 0 || !(opt.df > 0) || !(opt.scale > 0) ||
      !(opt.min_ess_fraction > 0 && opt.min_ess_fraction <= 1))
    throw std::invalid_argument("adapt_proposal: invalid options");
  AdaptedProposal a{mean, covariance};
  std::vector<TDensity> proposals;
  std::vector<Eigen::VectorXd> xs;
  std::vector<double> lp;
  for (int round = 0; round < opt.max_rounds; ++round) {
    Eigen::LLT<Eigen::MatrixXd> llt(opt.scale * opt.scale * a.covariance);
    if (llt.info() != Eigen::Success) {
      if (round == 0) throw std::invalid_argument("adapt_proposal: covariance not positive definite");
      break;
    }
    proposals.push_back(t_density(a.mean, llt.matrixL(), opt.df));
    const TDensity& q = proposals.back();
    std::vector<Eigen::VectorXd> batch(opt.points);
    for (auto& x : batch) {  // mean + L z / sqrt(w): a multivariate t
      Eigen::VectorXd z(d);
      for (Eigen::Index j = 0; j < d; ++j) z[j] = rng.normal();
      const double w = rng.gamma(0.5 * opt.df) / (0.5 * opt.df);
      x = q.mean + q.L * z / std::sqrt(w);
    }
    const std::vector<double> blp = log_densities(target, batch, nuisance);
    a.evaluations += opt.points;
    xs.insert(xs.end(), batch.begin(), batch.end());
    lp.insert(lp.end(), blp.begin(), blp.end());
    std::vector<double> log_w(xs.size());
    std::vector<double> mix(proposals.size());
    for (std::size_t i = 0; i < xs.size(); ++i) {
      if (!std::isfinite(lp[i])) {  // failed or outside the support: no weight
        log_w[i] = kNegInf;
        continue;
      }
      for (std::size_t r = 0; r < proposals.size(); ++r) mix[r] = proposals[r](xs[i]);
      log_w[i] = lp[i] - (log_sum_exp(mix) - std::log(double(proposals.size())));
    }
    const double beta = tempering_exponent(log_w, opt.min_ess_fraction * opt.points);
    const double ess = effective_sample_size(log_w, beta);
    if (!(ess >= double(d + 1))) break;  // too few points carry weight to fit a covariance: keep q
    double top = kNegInf;
    for (double v : log_w) top = std::max(top, v);
    Eigen::VectorXd m = Eigen::VectorXd::Zero(d);
    double total = 0;
    std::vector<double> w(xs.size(), 0.0);
    for (std::size_t i = 0; i < xs.size(); ++i) {
      if (!std::isfinite(log_w[i])) continue;
      w[i] = std::exp(beta * (log_w[i] - top));
      total += w[i];
      m += w[i] * xs[i];
    }
    m /= total;
    Eigen::MatrixXd c = Eigen::MatrixXd::Zero(d, d);
    for (std::size_t i = 0; i < xs.size(); ++i)
      if (w[i] > 0) c += (w[i] / total) * (xs[i] - m) * (xs[i] - m).transpose();
    if (Eigen::LLT<Eigen::MatrixXd>(c).info() != Eigen::Success || !c.allFinite()) break;
    a.mean = m;
    a.covariance = c;
    a.rounds = round + 1;
    a.beta = beta;
    a.ess = ess;
    if (beta == 1.0) {
      a.reached_posterior = true;
      if (ess >= opt.final_ess) break;
    }
  }
  return a;
}

}  // namespace terracal::bayes
