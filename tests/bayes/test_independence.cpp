// Independence Metropolis-Hastings (bayes/independence) on targets with known answers: a correlated
// Gaussian sampled through a deliberately imperfect t proposal, the batch and single evaluation paths
// (identical chains), failed evaluations, checkpoints, the proposal refit and the refused set-ups.
// Expectations are checked against 4 Monte Carlo standard errors from the multi-chain ESS.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "bayes/diagnostics.hpp"
#include "bayes/independence.hpp"
#include "bayes/json_state.hpp"

using namespace terracal::bayes;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using terracal::Rng;

namespace {

VectorXd vec(std::initializer_list<double> v) {
  VectorXd out(v.size());
  std::size_t i = 0;
  for (double e : v) out[i++] = e;
  return out;
}

double pooled_mean(const Chains& c) {
  double s = 0, n = 0;
  for (const auto& chain : c)
    for (double v : chain) s += v, n += 1;
  return s / n;
}

double pooled_sd(const Chains& c) {
  const double m = pooled_mean(c);
  double s = 0, n = 0;
  for (const auto& chain : c)
    for (double v : chain) s += (v - m) * (v - m), n += 1;
  return std::sqrt(s / (n - 1));
}

// Standard error of the pooled mean from the multi-chain ESS.
double mcse(const Chains& c) { return pooled_sd(c) / std::sqrt(ess_basic(c)); }

// A 3-D Gaussian with unequal scales and correlations 0.6, -0.3, 0.2.
struct Gauss3 {
  VectorXd mu = vec({1.0, -2.0, 0.5});
  VectorXd sd = vec({1.0, 2.0, 0.5});
  MatrixXd cov() const {
    MatrixXd r(3, 3);
    r << 1.0, 0.6, -0.3, 0.6, 1.0, 0.2, -0.3, 0.2, 1.0;
    return sd.asDiagonal() * r * sd.asDiagonal();
  }
  Target target() const {
    const MatrixXd l = cov().llt().matrixL();
    Target t;
    t.dim = 3;
    t.log_density = [mu = mu, l](const VectorXd& x, const VectorXd&) {
      return -0.5 * l.triangularView<Eigen::Lower>().solve(x - mu).squaredNorm();
    };
    return t;
  }
};

// y_i ~ N(mu, s2), mu | s2 ~ N(0, s2 / k0), s2 ~ InvGamma(a0, b0): mu is x, s2 the nuisance with its
// exact Gibbs step (as in test_samplers.cpp). Used where the nuisance's state must travel too.
struct NormalInverseGamma {
  std::vector<double> y;
  double k0 = 0.5, a0 = 3, b0 = 1;
  NormalInverseGamma() {
    Rng rng(2024);
    for (int i = 0; i < 10; ++i) y.push_back(2.0 + 0.5 * rng.normal());
  }
  double sum_sq(double mu) const {
    double s = k0 * mu * mu;
    for (double v : y) s += (v - mu) * (v - mu);
    return s;
  }
  Target target() const {
    Target t;
    t.dim = 1;
    t.nuisance_dim = 1;
    t.log_density = [this](const VectorXd& x, const VectorXd& s2) { return -0.5 * sum_sq(x[0]) / s2[0]; };
    t.gibbs = [this](const VectorXd& x, VectorXd& s2, Rng& rng) {
      s2[0] = (b0 + 0.5 * sum_sq(x[0])) / rng.gamma(a0 + 0.5 * double(y.size() + 1));
    };
    return t;
  }
};

std::vector<VectorXd> copies(int n, const VectorXd& v) { return std::vector<VectorXd>(n, v); }

// Per-chain histories of every coordinate: out[j][c][i].
std::vector<Chains> run_recording(IndependenceSampler& s, int steps) {
  const int d = int(s.states()[0].size());
  std::vector<Chains> out(d, Chains(s.size()));
  for (int i = 0; i < steps; ++i) {
    s.step();
    for (std::size_t k = 0; k < s.size(); ++k)
      for (int j = 0; j < d; ++j) out[j][k].push_back(s.states()[k][j]);
  }
  return out;
}

// Draws x[j][chain][step] of Gauss3 `g`: each mean and covariance entry (the expectation of
// (x_i - mu_i)(x_j - mu_j)) within 4 MCSE of the truth, the covariances also within 10 % of
// sd_i sd_j, and R-hat below 1.01; each coordinate's ESS at least `min_ess`.
void check_gauss3_draws(const Gauss3& g, const std::vector<Chains>& x, double min_ess) {
  const MatrixXd cov = g.cov();
  const std::size_t chains = x[0].size(), steps = x[0][0].size();
  for (int j = 0; j < 3; ++j) {
    const double m = pooled_mean(x[j]), se = mcse(x[j]), ess = ess_basic(x[j]);
    INFO("x" << j << ": mean " << m << ", truth " << g.mu[j] << ", MCSE " << se << ", ESS " << ess);
    CHECK(ess > min_ess);
    CHECK(std::abs(m - g.mu[j]) < 4 * se);
    CHECK(rhat_rank(x[j]) < 1.01);
  }
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) {
      Chains p(chains);
      for (std::size_t k = 0; k < chains; ++k)
        for (std::size_t n = 0; n < steps; ++n) p[k].push_back((x[i][k][n] - g.mu[i]) * (x[j][k][n] - g.mu[j]));
      const double c = pooled_mean(p), se = mcse(p);
      INFO("cov(" << i << "," << j << "): " << c << ", truth " << cov(i, j) << ", MCSE " << se);
      CHECK(std::abs(c - cov(i, j)) < 4 * se);
      CHECK(std::abs(c - cov(i, j)) < 0.1 * g.sd[i] * g.sd[j]);
    }
}

double pooled_acceptance(const IndependenceSampler& s) {
  double acc = 0, it = 0;
  for (const auto& st : s.stats()) acc += double(st.accepted), it += double(st.iterations);
  return acc / it;
}

// Student t with 4 degrees of freedom: P(T <= t) (closed form for even df).
double t4_cdf(double t) {
  const double u = t / std::sqrt(4.0 + t * t);
  return 0.5 + 0.5 * u * (1.5 - 0.5 * u * u);
}

// The Gaussian target N(mu, cov) and the multivariate t proposal (df, mean m, covariance scale^2 c)
// with exact draws of both and the log weight w = pi / q (up to a constant), for the stationary
// rates below.
struct GaussAndT {
  VectorXd mu, m;
  MatrixXd lp, lq;
  IndependenceOptions opt;
  GaussAndT(const VectorXd& mu_, const MatrixXd& cov, const IndependenceOptions& o, const VectorXd& m_,
            const MatrixXd& c)
      : mu(mu_), m(m_), lp(cov.llt().matrixL()), lq((o.scale * o.scale * c).llt().matrixL()), opt(o) {}
  double log_w(const VectorXd& x) const {
    const double p = -0.5 * lp.triangularView<Eigen::Lower>().solve(x - mu).squaredNorm();
    const double q = -0.5 * (opt.df + double(x.size())) *
                     std::log1p(lq.triangularView<Eigen::Lower>().solve(x - m).squaredNorm() / opt.df);
    return p - q;
  }
  VectorXd draw_target(Rng& rng) const {
    VectorXd z(mu.size());
    for (Eigen::Index j = 0; j < z.size(); ++j) z[j] = rng.normal();
    return mu + lp * z;
  }
  VectorXd draw_proposal(Rng& rng) const {
    VectorXd u(mu.size());
    for (Eigen::Index j = 0; j < u.size(); ++j) u[j] = rng.normal();
    const double w = rng.gamma(0.5 * opt.df) / (0.5 * opt.df);
    return m + lq * u / std::sqrt(w);
  }
};

// The stationary acceptance rate of an independence sampler, E min(1, w(y)/w(x)) with w = pi/q,
// x ~ pi and y ~ q independent (Tierney 1994), by plain Monte Carlo.
double stationary_acceptance(const VectorXd& mu, const MatrixXd& cov, const IndependenceOptions& opt, const VectorXd& m,
                             const MatrixXd& c, int n, std::uint64_t seed) {
  Rng rng(seed);
  const GaussAndT g(mu, cov, opt, m, c);
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const VectorXd x = g.draw_target(rng), y = g.draw_proposal(rng);
    sum += std::min(1.0, std::exp(g.log_w(y) - g.log_w(x)));
  }
  return sum / n;
}

// The probability that an i-SIR step keeps the state at stationarity, E[w(x) / (w(x) + sum_j w(y_j))]
// with x ~ pi and the tries - 1 points y_j ~ q, by plain Monte Carlo: a wrong weight or a wrong pick
// shows here.
double stationary_stay(const VectorXd& mu, const MatrixXd& cov, const IndependenceOptions& opt, const VectorXd& m,
                       const MatrixXd& c, int n, std::uint64_t seed) {
  Rng rng(seed);
  const GaussAndT g(mu, cov, opt, m, c);
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double wx = g.log_w(g.draw_target(rng));
    double others = 0;
    for (int t = 1; t < opt.tries; ++t) others += std::exp(g.log_w(g.draw_proposal(rng)) - wx);
    sum += 1.0 / (1.0 + others);
  }
  return sum / n;
}

// The whole state of a sampler, for bit-for-bit comparisons.
std::vector<double> snapshot(const IndependenceSampler& s) {
  std::vector<double> d;
  for (std::size_t k = 0; k < s.size(); ++k) {
    d.insert(d.end(), s.states()[k].data(), s.states()[k].data() + s.states()[k].size());
    d.insert(d.end(), s.nuisances()[k].data(), s.nuisances()[k].data() + s.nuisances()[k].size());
    d.push_back(s.log_densities()[k]);
    d.push_back(double(s.stats()[k].accepted));
    d.push_back(double(s.stats()[k].failed_evaluations));
  }
  return d;
}

// `t` with a batch evaluation that counts its calls and checks that each holds `expected` points (0:
// any number), with one nuisance per point.
Target counted_batches(const Target& t, std::size_t expected, int& calls, bool& sizes_ok) {
  Target batched = t;
  batched.log_density_batch = [t, expected, &calls, &sizes_ok](const std::vector<VectorXd>& xs,
                                                               const std::vector<VectorXd>& nus,
                                                               std::vector<double>& out) {
    ++calls;
    sizes_ok = sizes_ok && (expected == 0 || xs.size() == expected) && nus.size() == xs.size();
    out.resize(xs.size());
    for (std::size_t i = 0; i < xs.size(); ++i) out[i] = t.log_density(xs[i], nus[i]);
  };
  return batched;
}

}  // namespace

TEST_CASE("independence: an imperfect t proposal still samples a correlated 3-D Gaussian exactly",
          "[bayes][independence]") {
  const Gauss3 g;
  const Target t = g.target();
  const MatrixXd cov = g.cov();
  // Proposal mean 0.5 sd off in every coordinate, covariance twice the target's: a sampler that
  // left out the q(x)/q(y) factor would be pulled towards the proposal's mean (by far more than
  // 4 MCSE) and would show the proposal's spread.
  const VectorXd m0 = g.mu + 0.5 * g.sd;
  const int chains = 16, steps = 2000;
  IndependenceSampler s(t, IndependenceOptions{}, m0, 2.0 * cov, copies(chains, g.mu), copies(chains, VectorXd()),
                        Rng(11));
  const std::vector<Chains> x = run_recording(s, steps);
  // Nearly independent draws: an independence sampler that barely moves fails the ESS of 3000.
  check_gauss3_draws(g, x, 3000);
  // The acceptance rate is the one the kernel must have at stationarity (an error in the proposal's
  // density or in its draws shows here even where the moments above would hide it).
  const double acc = pooled_acceptance(s);
  const double theory = stationary_acceptance(g.mu, cov, IndependenceOptions{}, m0, 2.0 * cov, 200000, 12);
  INFO("acceptance " << acc << ", stationary value " << theory);
  CHECK(std::abs(acc - theory) < 0.02);
  CHECK(acc > 0.25);
  for (const auto& st : s.stats()) {
    CHECK(st.iterations == steps);
    CHECK(st.failed_evaluations == 0);
  }
}

TEST_CASE("independence: one batch call per step, and the same chains as with single evaluations",
          "[bayes][independence]") {
  const NormalInverseGamma nig;  // with a nuisance: the Gibbs step and its re-evaluation are in the loop
  const Target single = nig.target();
  Target batched = single;
  int batch_calls = 0, single_calls = 0;
  std::vector<VectorXd> expected_nuisances;
  bool sizes_ok = true, nuisances_ok = true;
  batched.log_density = [&](const VectorXd& x, const VectorXd& s2) {
    ++single_calls;
    return single.log_density(x, s2);
  };
  batched.log_density_batch = [&](const std::vector<VectorXd>& xs, const std::vector<VectorXd>& nus,
                                  std::vector<double>& out) {
    ++batch_calls;
    sizes_ok = sizes_ok && xs.size() == 8 && nus.size() == 8;
    nuisances_ok = nuisances_ok && nus == expected_nuisances;  // the chains' current nuisances
    out.resize(xs.size());
    for (std::size_t i = 0; i < xs.size(); ++i) out[i] = single.log_density(xs[i], nus[i]);
  };
  const int chains = 8, steps = 300;
  std::vector<VectorXd> starts;
  for (int k = 0; k < chains; ++k) starts.push_back(vec({1.5 + 0.1 * k}));
  const std::vector<VectorXd> nus = copies(chains, vec({0.3}));
  IndependenceSampler a(single, IndependenceOptions{}, vec({1.8}), MatrixXd::Constant(1, 1, 0.05), starts, nus,
                        Rng(21));
  IndependenceSampler b(batched, IndependenceOptions{}, vec({1.8}), MatrixXd::Constant(1, 1, 0.05), starts, nus,
                        Rng(21));
  single_calls = 0;  // the starts' evaluations
  long moves = 0;
  for (int i = 0; i < steps; ++i) {
    a.step();
    expected_nuisances = b.nuisances();
    b.step();
    REQUIRE(batch_calls == i + 1);
    // After the batch only the Gibbs re-evaluation of each chain's own state: one per chain.
    REQUIRE(single_calls == chains * (i + 1));
    REQUIRE(snapshot(a) == snapshot(b));
  }
  CHECK(sizes_ok);
  CHECK(nuisances_ok);
  for (const auto& st : b.stats()) moves += st.accepted;
  CHECK(moves > chains * steps / 4);  // the chains did move: the comparison is not of frozen states
  CHECK(a.save() == b.save());
}

TEST_CASE("independence: failed evaluations are rejected and counted, the chain never enters their region",
          "[bayes][independence]") {
  // Standard normal in 2-D whose density is NaN for x1 > 1: the chains sample the normal truncated
  // to x1 <= 1, E x1 = -phi(1)/Phi(1). Each proposal is evaluated once, so the failures of a chain
  // are a binomial count with p = P(proposal has x1 > 1), the t4 proposal's marginal being t4 with
  // scale `scale` (1.3) about 0.
  Target t;
  t.dim = 2;
  t.log_density = [](const VectorXd& x, const VectorXd&) {
    return x[0] > 1 ? std::numeric_limits<double>::quiet_NaN() : -0.5 * x.squaredNorm();
  };
  Target tb = t;  // the same through the batch path, its first call throwing (every point failed)
  int calls = 0;
  tb.log_density_batch = [&](const std::vector<VectorXd>& xs, const std::vector<VectorXd>& nus,
                             std::vector<double>& out) {
    if (calls++ == 0) throw std::runtime_error("the forward model broke");
    out.resize(xs.size());
    for (std::size_t i = 0; i < xs.size(); ++i) out[i] = t.log_density(xs[i], nus[i]);
  };
  const int chains = 8, steps = 2000;
  IndependenceSampler s(t, IndependenceOptions{}, vec({0, 0}), MatrixXd::Identity(2, 2), copies(chains, vec({0, 0})),
                        copies(chains, VectorXd()), Rng(31));
  IndependenceSampler sb(tb, IndependenceOptions{}, vec({0, 0}), MatrixXd::Identity(2, 2), copies(chains, vec({0, 0})),
                         copies(chains, VectorXd()), Rng(31));
  std::vector<Chains> x(2, Chains(chains));
  bool finite = true, outside = false;
  for (int i = 0; i < steps; ++i) {
    s.step();
    sb.step();
    for (int k = 0; k < chains; ++k) {
      finite = finite && s.states()[k].allFinite() && std::isfinite(s.log_densities()[k]);
      outside = outside || s.states()[k][0] > 1 || sb.states()[k][0] > 1;
      for (int j = 0; j < 2; ++j) x[j][k].push_back(s.states()[k][j]);
    }
  }
  CHECK(finite);
  CHECK_FALSE(outside);
  const double p = 1 - t4_cdf(1 / IndependenceOptions{}.scale);
  long failed = 0;
  for (const auto& st : s.stats()) {
    CHECK(st.iterations == steps);
    CHECK(st.failed_evaluations > 0);
    failed += st.failed_evaluations;
  }
  const double n = double(chains) * steps, sd = std::sqrt(n * p * (1 - p));
  INFO("failed " << failed << ", expected " << n * p << " +- " << sd);
  CHECK(std::abs(double(failed) - n * p) < 5 * sd);
  // The throwing batch counted one failure for every chain, on top of the same NaN region.
  long failed_b = 0;
  for (const auto& st : sb.stats()) failed_b += st.failed_evaluations;
  CHECK(std::abs(double(failed_b - chains) - n * p) < 5 * sd);

  const double phi1 = std::exp(-0.5) / std::sqrt(2 * std::numbers::pi), Phi1 = 0.5 * std::erfc(-1 / std::sqrt(2.0));
  const double m1 = pooled_mean(x[0]), se1 = mcse(x[0]), m2 = pooled_mean(x[1]), se2 = mcse(x[1]);
  INFO("E x1 " << m1 << " (truth " << -phi1 / Phi1 << ", MCSE " << se1 << "), E x2 " << m2 << " (MCSE " << se2 << ")");
  CHECK(std::abs(m1 + phi1 / Phi1) < 4 * se1);
  CHECK(std::abs(m2) < 4 * se2);
}

TEST_CASE("independence: save and load continue with bit-identical states", "[bayes][independence]") {
  const NormalInverseGamma nig;  // nuisances and their Gibbs draws are part of the state
  const Target t = nig.target();
  const int chains = 6;
  std::vector<VectorXd> starts;
  for (int k = 0; k < chains; ++k) starts.push_back(vec({1.0 + 0.2 * k}));
  IndependenceSampler s(t, IndependenceOptions{}, vec({1.5}), MatrixXd::Constant(1, 1, 0.2), starts,
                        copies(chains, vec({0.5})), Rng(41));
  std::vector<VectorXd> pool;
  for (int i = 0; i < 50; ++i) {
    s.step();
    pool.insert(pool.end(), s.states().begin(), s.states().end());
  }
  s.refit(pool);                              // the refitted proposal is part of what must be saved
  const std::string saved = s.save().dump();  // through text: doubles must round-trip exactly

  auto record = [](IndependenceSampler& x) {
    std::vector<double> d;
    for (int i = 0; i < 50; ++i) {
      x.step();
      const std::vector<double> snap = snapshot(x);
      d.insert(d.end(), snap.begin(), snap.end());
    }
    return d;
  };
  const std::vector<double> d1 = record(s);
  // Another proposal, other starts, nuisances and seed: everything must come from the checkpoint.
  IndependenceSampler fresh(t, IndependenceOptions{}, vec({0.0}), MatrixXd::Constant(1, 1, 3.0),
                            copies(chains, vec({2.0})), copies(chains, vec({1.0})), Rng(5));
  fresh.load(nlohmann::json::parse(saved));
  const std::vector<double> d2 = record(fresh);
  REQUIRE(d1.size() == d2.size());
  CHECK(d1 == d2);
  CHECK(fresh.save() == s.save());
  for (const auto& st : fresh.stats()) CHECK(st.iterations == 100);

  // A foreign or mis-sized checkpoint is refused and leaves the sampler as it was.
  const nlohmann::json before = fresh.save();
  nlohmann::json foreign = before;
  foreign["sampler"] = "dram";
  CHECK_THROWS_AS(fresh.load(foreign), std::invalid_argument);
  nlohmann::json short_of_a_chain = before;
  short_of_a_chain["log_densities"].erase(0);
  CHECK_THROWS(fresh.load(short_of_a_chain));
  CHECK(fresh.save() == before);
}

TEST_CASE("independence: refit to draws of the target raises the acceptance of a far too wide proposal",
          "[bayes][independence]") {
  const Gauss3 g;
  const Target t = g.target();
  const MatrixXd cov = g.cov();
  const int chains = 16, steps = 300;
  // Proposal 100 times the target's covariance (10 times its sd), centred 2 sd off: nearly every
  // draw lands where the target is negligible.
  IndependenceSampler s(t, IndependenceOptions{}, g.mu + 2 * g.sd, 100.0 * cov, copies(chains, g.mu),
                        copies(chains, VectorXd()), Rng(51));
  for (int i = 0; i < steps; ++i) s.step();
  const double before = pooled_acceptance(s);

  // Exact draws of the target; too few of them (< 4 dim) or a degenerate set leave the proposal as is.
  Rng rng(52);
  const MatrixXd l = cov.llt().matrixL();
  std::vector<VectorXd> draws;
  for (int n = 0; n < 4000; ++n) {
    VectorXd z(3);
    for (int j = 0; j < 3; ++j) z[j] = rng.normal();
    draws.push_back(g.mu + l * z);
  }
  const nlohmann::json proposal0 = s.save();
  s.refit(std::vector<VectorXd>(draws.begin(), draws.begin() + 11));
  CHECK(s.save() == proposal0);
  s.refit(copies(40, g.mu));  // zero covariance: not positive definite
  CHECK(s.save() == proposal0);

  s.refit(draws);
  // The refitted proposal: the draws' mean, and their covariance times scale^2.
  const nlohmann::json j = s.save();
  const VectorXd mean = vector_from_json(j.at("mean"), 3);
  const MatrixXd chol = matrix_from_json(j.at("chol"), 3, 3);
  const MatrixXd fitted = chol * chol.transpose();
  const double s2 = IndependenceOptions{}.scale * IndependenceOptions{}.scale;
  for (int a = 0; a < 3; ++a) {
    CHECK(std::abs(mean[a] - g.mu[a]) < 5 * g.sd[a] / std::sqrt(4000.0));
    for (int b = 0; b < 3; ++b) CHECK(std::abs(fitted(a, b) / s2 - cov(a, b)) < 0.1 * std::sqrt(cov(a, a) * cov(b, b)));
  }

  // The chains' proposal densities are those of the new proposal, -0.5 (df + d) log(1 + |L^-1 (x - m)|^2 / df):
  // left at the old ones, the first move after a refit would use the wrong Hastings ratio.
  const double df = IndependenceOptions{}.df;
  for (std::size_t k = 0; k < s.size(); ++k) {
    const VectorXd z = chol.triangularView<Eigen::Lower>().solve(s.states()[k] - mean);
    CHECK(decode_double(j.at("log_proposals")[k]) ==
          Approx(-0.5 * (df + 3) * std::log1p(z.squaredNorm() / df)).epsilon(1e-12).margin(1e-14));
  }

  std::vector<long> acc0, it0;
  for (const auto& st : s.stats()) acc0.push_back(st.accepted), it0.push_back(st.iterations);
  const std::vector<Chains> x = run_recording(s, steps);
  double acc = 0, it = 0;
  for (std::size_t k = 0; k < s.size(); ++k)
    acc += double(s.stats()[k].accepted - acc0[k]), it += double(s.stats()[k].iterations - it0[k]);
  const double after = acc / it;
  const double theory = stationary_acceptance(g.mu, cov, IndependenceOptions{}, mean, fitted / s2, 200000, 53);
  INFO("acceptance before refit " << before << ", after " << after << " (stationary value " << theory << ")");
  CHECK(before < 0.1);
  CHECK(after > 0.5);
  CHECK(std::abs(after - theory) < 0.04);
  // And the chains still sample the target after the proposal changed under them.
  for (int j2 = 0; j2 < 3; ++j2) CHECK(std::abs(pooled_mean(x[j2]) - g.mu[j2]) < 4 * mcse(x[j2]));
}

TEST_CASE("independence: invalid set-ups are refused", "[bayes][independence]") {
  // Log density -inf for x1 < 0 (outside the support), NaN for x2 > 5 (a failed evaluation).
  Target t;
  t.dim = 2;
  t.log_density = [](const VectorXd& x, const VectorXd&) {
    if (x[0] < 0) return -std::numeric_limits<double>::infinity();
    return x[1] > 5 ? std::numeric_limits<double>::quiet_NaN() : -0.5 * x.squaredNorm();
  };
  const VectorXd m = vec({1, 1});
  const MatrixXd eye = MatrixXd::Identity(2, 2);
  const auto none = copies(2, VectorXd());
  const auto ok = copies(2, vec({1, 1}));
  CHECK_NOTHROW(IndependenceSampler(t, {}, m, eye, ok, none, Rng(1)));
  MatrixXd indefinite(2, 2);
  indefinite << 1, 2, 2, 1;
  CHECK_THROWS_AS(IndependenceSampler(t, {}, m, -eye, ok, none, Rng(1)), std::invalid_argument);
  CHECK_THROWS_AS(IndependenceSampler(t, {}, m, indefinite, ok, none, Rng(1)), std::invalid_argument);
  CHECK_THROWS_AS(IndependenceSampler(t, {}, m, MatrixXd::Zero(2, 2), ok, none, Rng(1)), std::invalid_argument);
  // Starts outside the support, or where the density fails.
  CHECK_THROWS_AS(IndependenceSampler(t, {}, m, eye, {vec({1, 1}), vec({-1, 1})}, none, Rng(1)), std::invalid_argument);
  CHECK_THROWS_AS(IndependenceSampler(t, {}, m, eye, {vec({1, 6}), vec({1, 1})}, none, Rng(1)), std::invalid_argument);
  // Sizes: proposal mean, covariance, a start, the nuisance count, no chain at all.
  CHECK_THROWS_AS(IndependenceSampler(t, {}, vec({1}), eye, ok, none, Rng(1)), std::invalid_argument);
  CHECK_THROWS_AS(IndependenceSampler(t, {}, m, MatrixXd::Identity(3, 3), ok, none, Rng(1)), std::invalid_argument);
  CHECK_THROWS_AS(IndependenceSampler(t, {}, m, MatrixXd::Identity(2, 3), ok, none, Rng(1)), std::invalid_argument);
  CHECK_THROWS_AS(IndependenceSampler(t, {}, m, eye, {vec({1, 1}), vec({1, 1, 1})}, none, Rng(1)),
                  std::invalid_argument);
  CHECK_THROWS_AS(IndependenceSampler(t, {}, m, eye, ok, copies(3, VectorXd()), Rng(1)), std::invalid_argument);
  CHECK_THROWS_AS(IndependenceSampler(t, {}, m, eye, {}, {}, Rng(1)), std::invalid_argument);
  // A nuisance of the wrong size for a target that has one.
  const NormalInverseGamma nig;
  const Target tn = nig.target();
  CHECK_THROWS_AS(
      IndependenceSampler(tn, {}, vec({1}), MatrixXd::Ones(1, 1), copies(2, vec({1})), copies(2, vec({1, 1})), Rng(1)),
      std::invalid_argument);
  CHECK_THROWS_AS(
      IndependenceSampler(tn, {}, vec({1}), MatrixXd::Ones(1, 1), copies(2, vec({1})), copies(2, VectorXd()), Rng(1)),
      std::invalid_argument);
  // Options: df and scale must be positive.
  CHECK_THROWS_AS(IndependenceSampler(t, {.df = 0.0}, m, eye, ok, none, Rng(1)), std::invalid_argument);
  CHECK_THROWS_AS(IndependenceSampler(t, {.scale = -1.0}, m, eye, ok, none, Rng(1)), std::invalid_argument);
  CHECK_THROWS_AS(IndependenceSampler(t, {.tries = 0}, m, eye, ok, none, Rng(1)), std::invalid_argument);
  // Delayed acceptance screens the random-walk move: without it there is nothing to screen.
  CHECK_NOTHROW(IndependenceSampler(t, {.local_moves = true, .delayed_acceptance = true}, m, eye, ok, none, Rng(1)));
  CHECK_THROWS_AS(IndependenceSampler(t, {.delayed_acceptance = true}, m, eye, ok, none, Rng(1)),
                  std::invalid_argument);
}

TEST_CASE("independence: i-SIR with an imperfect t proposal samples a correlated 3-D Gaussian exactly",
          "[bayes][independence]") {
  const Gauss3 g;
  const Target t = g.target();
  const MatrixXd cov = g.cov();
  // The proposal of the Metropolis test above: off by 0.5 sd, twice as wide. Picking by pi instead
  // of pi / q would pull the draws to the proposal's mean; a pick that ignored the current state
  // would sample the weighted proposal, not pi, and shows in the stay probability.
  const VectorXd m0 = g.mu + 0.5 * g.sd;
  const IndependenceOptions opt{.tries = 8};
  const int chains = 16, steps = 600;
  int calls = 0;
  bool sizes_ok = true;
  const Target batched = counted_batches(t, std::size_t(chains * (opt.tries - 1)), calls, sizes_ok);
  IndependenceSampler s(batched, opt, m0, 2.0 * cov, copies(chains, g.mu), copies(chains, VectorXd()), Rng(31));
  const std::vector<Chains> x = run_recording(s, steps);
  CHECK(calls == steps);  // one batch of chains x (tries - 1) points per step
  CHECK(sizes_ok);
  check_gauss3_draws(g, x, 0.45 * chains * steps);  // nearly independent draws with 8 tries (one try: about 0.2)
  const double stay = 1.0 - pooled_acceptance(s);
  const double theory = stationary_stay(g.mu, cov, opt, m0, 2.0 * cov, 100000, 32);
  INFO("stay " << stay << ", stationary value " << theory);
  CHECK(std::abs(stay - theory) < 0.02);
  // Seven fresh points leave the chain where it is far less often than one Metropolis try does.
  const double mh_stay = 1.0 - stationary_acceptance(g.mu, cov, IndependenceOptions{}, m0, 2.0 * cov, 100000, 33);
  INFO("Metropolis-Hastings stays with probability " << mh_stay);
  CHECK(stay < 0.6 * mh_stay);
}

TEST_CASE("independence: i-SIR never picks a failed point, and evaluates each chain's tries with its nuisance",
          "[bayes][independence]") {
  const NormalInverseGamma nig;
  Target t = nig.target();
  const Target plain = nig.target();
  // Failed (NaN) above mu = 2.1: the chains sample the posterior truncated there.
  t.log_density = [&](const VectorXd& x, const VectorXd& s2) {
    return x[0] > 2.1 ? std::numeric_limits<double>::quiet_NaN() : plain.log_density(x, s2);
  };
  std::vector<VectorXd> expected;
  bool nuisances_ok = true;
  const int chains = 6, tries = 5;
  t.log_density_batch = [&](const std::vector<VectorXd>& xs, const std::vector<VectorXd>& nus,
                            std::vector<double>& out) {
    for (std::size_t i = 0; i < xs.size(); ++i) nuisances_ok = nuisances_ok && nus[i] == expected[i / (tries - 1)];
    out.resize(xs.size());
    for (std::size_t i = 0; i < xs.size(); ++i) out[i] = t.log_density(xs[i], nus[i]);
  };
  std::vector<VectorXd> starts;
  for (int k = 0; k < chains; ++k) starts.push_back(vec({1.7 + 0.05 * k}));
  std::vector<VectorXd> nus;
  for (int k = 0; k < chains; ++k) nus.push_back(vec({0.2 + 0.02 * k}));  // every chain its own
  IndependenceSampler s(t, {.tries = tries}, vec({2.0}), MatrixXd::Constant(1, 1, 0.04), starts, nus, Rng(5));
  double highest = 0;
  for (int i = 0; i < 400; ++i) {
    expected = s.nuisances();
    s.step();
    for (const auto& x : s.states()) highest = std::max(highest, x[0]);
  }
  CHECK(nuisances_ok);
  CHECK(highest <= 2.1);
  long failed = 0, moved = 0;
  for (const auto& st : s.stats()) failed += st.failed_evaluations, moved += st.accepted;
  CHECK(failed > 100);  // the proposal reaches past 2.1 often: the failures were met and counted
  CHECK(moved > chains * 400 / 2);
}

TEST_CASE("independence: proposals drawn ahead for several steps: one batch per lookahead, the same posterior",
          "[bayes][independence]") {
  const Gauss3 g;
  const Target t = g.target();
  const MatrixXd cov = g.cov();
  const VectorXd m0 = g.mu + 0.5 * g.sd;  // the imperfect proposal of the i-SIR test above
  const int chains = 16, steps = 600;
  for (const IndependenceOptions opt :
       {IndependenceOptions{.tries = 8, .lookahead = 3}, IndependenceOptions{.tries = 1, .lookahead = 4}}) {
    const std::size_t per = std::size_t(std::max(opt.tries - 1, 1));
    int calls = 0;
    bool sizes_ok = true;
    const Target batched = counted_batches(t, chains * per * std::size_t(opt.lookahead), calls, sizes_ok);
    IndependenceSampler s(batched, opt, m0, 2.0 * cov, copies(chains, g.mu), copies(chains, VectorXd()), Rng(31));
    const std::vector<Chains> x = run_recording(s, steps);
    INFO("tries " << opt.tries << ", lookahead " << opt.lookahead);
    CHECK(calls == steps / opt.lookahead);
    CHECK(sizes_ok);
    for (int j = 0; j < 3; ++j) {
      const double m = pooled_mean(x[j]), se = mcse(x[j]), sd = pooled_sd(x[j]);
      INFO("x" << j << ": mean " << m << ", truth " << g.mu[j] << ", MCSE " << se << ", sd " << sd);
      CHECK(std::abs(m - g.mu[j]) < 4 * se);
      CHECK(std::abs(sd - g.sd[j]) < 0.1 * g.sd[j]);
    }
    // The stay probability is the kernel's: a step that reused another step's proposals, or weighed
    // them with the wrong state, would show here.
    const double stay = 1.0 - pooled_acceptance(s);
    const double theory = opt.tries > 1 ? stationary_stay(g.mu, cov, opt, m0, 2.0 * cov, 100000, 32)
                                        : 1.0 - stationary_acceptance(g.mu, cov, opt, m0, 2.0 * cov, 100000, 33);
    INFO("stay " << stay << ", stationary value " << theory);
    CHECK(std::abs(stay - theory) < 0.02);
  }
}

TEST_CASE("independence: proposals drawn ahead survive a checkpoint and are dropped by a refit",
          "[bayes][independence]") {
  const Gauss3 g;
  const Target plain = g.target();
  int calls = 0;
  bool sizes_ok = true;
  const Target t = counted_batches(plain, 0, calls, sizes_ok);
  const IndependenceOptions opt{.tries = 4, .lookahead = 3};
  const int chains = 4;
  IndependenceSampler s(t, opt, g.mu, g.cov(), copies(chains, g.mu), copies(chains, VectorXd()), Rng(7));
  for (int i = 0; i < 7; ++i) s.step();  // two batches; the second's last two steps are still ahead
  REQUIRE(calls == 3);
  const std::string saved = s.save().dump();
  IndependenceSampler fresh(t, opt, VectorXd::Zero(3), 3.0 * g.cov(), copies(chains, g.mu + g.sd),
                            copies(chains, VectorXd()), Rng(99));
  fresh.load(nlohmann::json::parse(saved));
  calls = 0;
  for (int i = 0; i < 2; ++i) {
    s.step();
    fresh.step();
    REQUIRE(snapshot(s) == snapshot(fresh));
  }
  CHECK(calls == 0);  // both served the two steps from the proposals drawn ahead
  for (int i = 0; i < 9; ++i) {
    s.step();
    fresh.step();
  }
  CHECK(snapshot(s) == snapshot(fresh));
  CHECK(calls == 6);

  // A refit changes the proposal: what was drawn from the old one is dropped, the next step draws anew.
  s.step();  // one of three steps used
  std::vector<VectorXd> pool;
  Rng rng(3);
  const MatrixXd l = g.cov().llt().matrixL();
  for (int i = 0; i < 200; ++i) {
    VectorXd z(3);
    for (int j = 0; j < 3; ++j) z[j] = rng.normal();
    pool.push_back(g.mu + l * z);
  }
  calls = 0;
  s.refit(pool);
  s.step();
  CHECK(calls == 1);
  CHECK(s.save().at("ahead").size() == std::size_t(2 * chains * (opt.tries - 1)));

  // Lookahead needs moves that do not depend on a chain's own nuisance, and at least one step.
  const NormalInverseGamma nig;
  CHECK_THROWS_AS(IndependenceSampler(nig.target(), {.lookahead = 2}, vec({1}), MatrixXd::Ones(1, 1),
                                      copies(2, vec({1})), copies(2, vec({1})), Rng(1)),
                  std::invalid_argument);
  CHECK_THROWS_AS(
      IndependenceSampler(plain, {.lookahead = 0}, g.mu, g.cov(), copies(2, g.mu), copies(2, VectorXd()), Rng(1)),
      std::invalid_argument);
}

namespace {

// The share of random-walk moves that pass delayed acceptance's first stage at stationarity (x ~ pi),
// E min(1, pit(y) / pit(x)) with y = x + (2.38 / sqrt(d)) L z, by plain Monte Carlo; the surrogate
// pit is the t with the proposal's degrees of freedom, mean m and covariance c (without `scale`).
double stationary_first_stage(const VectorXd& mu, const MatrixXd& cov, const IndependenceOptions& opt,
                              const VectorXd& m, const MatrixXd& c, int n, std::uint64_t seed) {
  Rng rng(seed);
  const GaussAndT g(mu, cov, opt, m, c);
  const MatrixXd lc = c.llt().matrixL();
  const auto log_pit = [&](const VectorXd& x) {
    return -0.5 * (opt.df + double(x.size())) *
           std::log1p(lc.triangularView<Eigen::Lower>().solve(x - m).squaredNorm() / opt.df);
  };
  const double step = 2.38 / std::sqrt(double(mu.size()));
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const VectorXd x = g.draw_target(rng);
    VectorXd z(mu.size());
    for (Eigen::Index j = 0; j < z.size(); ++j) z[j] = rng.normal();
    sum += std::min(1.0, std::exp(log_pit(x + step * (lc * z)) - log_pit(x)));
  }
  return sum / n;
}

}  // namespace

TEST_CASE(
    "independence: delayed acceptance samples a correlated 3-D Gaussian exactly through a wrong surrogate, "
    "and runs only the random-walk moves that pass it",
    "[bayes][independence]") {
  const Gauss3 g;
  const MatrixXd cov = g.cov();
  // The surrogate is the proposal's mean and covariance: 0.5 sd off and twice as wide, so a second
  // stage that did not divide the surrogate out would leave draws pulled towards its mean and spread.
  const VectorXd m0 = g.mu + 0.5 * g.sd;
  const int chains = 16, steps = 2000;
  int calls = 0;
  bool sizes_ok = true;
  long evaluated = 0;
  Target t = counted_batches(g.target(), 0, calls, sizes_ok);
  const auto batch = t.log_density_batch;
  t.log_density_batch = [&evaluated, batch](const std::vector<VectorXd>& xs, const std::vector<VectorXd>& nus,
                                            std::vector<double>& out) {
    evaluated += long(xs.size());
    batch(xs, nus, out);
  };
  const IndependenceOptions opt{.local_moves = true, .delayed_acceptance = true};
  IndependenceSampler s(t, opt, m0, 2.0 * cov, copies(chains, g.mu), copies(chains, VectorXd()), Rng(23));
  const std::vector<Chains> x = run_recording(s, steps);
  check_gauss3_draws(g, x, 3000);
  // Runs: every independence move, and exactly the random-walk moves that pass the first stage, at
  // the rate that stage has at stationarity; a sampler that ran every move (2 a step), or screened
  // with another surrogate, misses it.
  const double first_local = stationary_first_stage(g.mu, cov, opt, m0, 2.0 * cov, 200000, 24);
  const double per_chain_step = double(evaluated) / (double(chains) * steps);
  INFO("runs per chain and step " << per_chain_step << ", 1 + the stationary first-stage rate " << first_local);
  CHECK(sizes_ok);
  CHECK(std::abs(per_chain_step - (1.0 + first_local)) < 0.02);
  CHECK(per_chain_step < 1.6);
}

TEST_CASE("independence: delayed acceptance samples logistic coordinates exactly through a t surrogate",
          "[bayes][independence]") {
  // Independent logistic coordinates (mean 0, variance pi^2 / 3): the shape of a posterior that fills
  // its prior box, in the sampler's logit coordinates. The surrogate, a t of the same mean and
  // covariance, differs from pi in shape everywhere (its centre is flatter, its tails heavier), so the
  // second stage's correction is at work at every move, not only where the surrogate is misplaced.
  constexpr int d = 3;
  Target t;
  t.dim = d;
  t.log_density = [](const VectorXd& x, const VectorXd&) {
    double s = 0;
    for (int j = 0; j < d; ++j) s += -std::abs(x[j]) - 2.0 * std::log1p(std::exp(-std::abs(x[j])));
    return s;
  };
  const double var = std::numbers::pi * std::numbers::pi / 3.0;
  const int chains = 16, steps = 2000;
  const IndependenceOptions opt{.local_moves = true, .delayed_acceptance = true};
  IndependenceSampler s(t, opt, VectorXd::Zero(d), var * MatrixXd::Identity(d, d), copies(chains, VectorXd::Zero(d)),
                        copies(chains, VectorXd()), Rng(31));
  const std::vector<Chains> x = run_recording(s, steps);
  for (int j = 0; j < d; ++j) {
    Chains sq(chains), tail(chains);
    for (int k = 0; k < chains; ++k)
      for (double v : x[j][k]) {
        sq[k].push_back(v * v);
        tail[k].push_back(std::abs(v) > 3.0 ? 1.0 : 0.0);
      }
    // P(|x| > 3) = 2 / (1 + e^3) for a logistic.
    const double p_tail = 2.0 / (1.0 + std::exp(3.0));
    const double m = pooled_mean(x[j]), v = pooled_mean(sq), pt = pooled_mean(tail);
    INFO("x" << j << ": mean " << m << " (MCSE " << mcse(x[j]) << "), E x^2 " << v << " (MCSE " << mcse(sq)
             << ", truth " << var << "), P(|x| > 3) " << pt << " (MCSE " << mcse(tail) << ", truth " << p_tail
             << "), ESS " << ess_basic(sq));
    CHECK(std::abs(m) < 4 * mcse(x[j]));
    CHECK(std::abs(v - var) < 4 * mcse(sq));
    CHECK(std::abs(pt - p_tail) < 4 * mcse(tail));
    CHECK(rhat_rank(sq) < 1.01);
  }
}
