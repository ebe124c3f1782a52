// DRAM and the affine-invariant ensemble sampler on targets with known answers. Every check of an
// expectation allows 5 Monte Carlo standard errors, the standard error taken from the multi-chain
// ESS (bayes/diagnostics), and requires a minimum ESS so that a sampler that barely moves cannot
// pass on a wide tolerance.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bayes/diagnostics.hpp"
#include "bayes/dram.hpp"
#include "bayes/ensemble.hpp"
#include "bayes/json_state.hpp"

using namespace terracal::bayes;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using terracal::Rng;

namespace {

using Statistic = std::function<double(const VectorXd& x, const VectorXd& nuisance)>;
struct Expectation {
  std::string name;
  Statistic f;
  double truth;
};

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

// values[e][c][i] = statistic e at draw i of chain c.
void check_expectations(const std::vector<Expectation>& es, const std::vector<Chains>& values, double min_ess) {
  for (std::size_t e = 0; e < es.size(); ++e) {
    const double mean = pooled_mean(values[e]), ess = ess_basic(values[e]);
    const double se = pooled_sd(values[e]) / std::sqrt(ess);
    INFO(es[e].name << ": estimate " << mean << ", truth " << es[e].truth << ", MCSE " << se << ", ESS " << ess);
    CHECK(ess > min_ess);
    CHECK(std::abs(mean - es[e].truth) < 5 * se);
    CHECK(rhat_rank(values[e]) < 1.05);
  }
}

std::vector<Chains> empty_values(std::size_t n_stats, int chains) {
  return std::vector<Chains>(n_stats, Chains(chains));
}

// Independent DRAM chains: `warmup` adaptive steps, then `draws` steps with the proposal frozen
// (a fixed kernel, exactly invariant), recording each statistic.
struct DramRun {
  std::vector<Chains> values;
  std::vector<DramChain> chains;
};
DramRun run_dram(const Target& t, const std::vector<Expectation>& es, const VectorXd& x0, const VectorXd& nu0,
                 const MatrixXd& cov0, const DramOptions& opt, int warmup, int draws, std::uint64_t seed,
                 int n_chains = 4) {
  DramRun run{empty_values(es.size(), n_chains), {}};
  for (int c = 0; c < n_chains; ++c) {
    DramChain& chain = run.chains.emplace_back(t, opt, x0, nu0, cov0, Rng::for_stream(seed, c));
    for (int i = 0; i < warmup; ++i) chain.step(true);
    for (int i = 0; i < draws; ++i) {
      chain.step(false);
      for (std::size_t e = 0; e < es.size(); ++e) run.values[e][c].push_back(es[e].f(chain.x(), chain.nuisance()));
    }
  }
  return run;
}

// Independent ensembles; a draw is the ensemble average of the statistic at one step. Walkers of
// one ensemble are correlated with each other, the averages of separate ensembles are not, so
// the ESS of these averages gives an honest standard error.
struct EnsembleRun {
  std::vector<Chains> values;
  std::vector<EnsembleSampler> samplers;
};
EnsembleRun run_ensemble(const Target& t, const std::vector<Expectation>& es, const VectorXd& start,
                         const VectorXd& spread, const VectorXd& nu0, int n_walkers, int warmup, int draws,
                         std::uint64_t seed, int n_ensembles = 4) {
  EnsembleRun run{empty_values(es.size(), n_ensembles), {}};
  for (int c = 0; c < n_ensembles; ++c) {
    Rng init = Rng::for_stream(seed, 1000 + c);
    std::vector<VectorXd> walkers, nuisances;
    for (int k = 0; k < n_walkers; ++k) {
      VectorXd w = start;
      for (Eigen::Index i = 0; i < w.size(); ++i) w[i] += spread[i] * init.normal();
      walkers.push_back(w);
      if (nu0.size() > 0) nuisances.push_back(nu0);
    }
    EnsembleSampler& s = run.samplers.emplace_back(t, EnsembleOptions{}, walkers, nuisances, Rng::for_stream(seed, c));
    for (int i = 0; i < warmup; ++i) s.step();
    for (int i = 0; i < draws; ++i) {
      s.step();
      for (std::size_t e = 0; e < es.size(); ++e) {
        double avg = 0;
        for (std::size_t k = 0; k < s.size(); ++k) avg += es[e].f(s.walkers()[k], s.nuisances()[k]) / double(s.size());
        run.values[e][c].push_back(avg);
      }
    }
  }
  return run;
}

// --- targets with known moments -----------------------------------------------------------

Target gaussian(const VectorXd& mu, const MatrixXd& cov) {
  const MatrixXd l = cov.llt().matrixL();
  Target t;
  t.dim = int(mu.size());
  t.log_density = [mu, l](const VectorXd& x, const VectorXd&) {
    return -0.5 * l.triangularView<Eigen::Lower>().solve(x - mu).squaredNorm();
  };
  return t;
}

// sd 1e3 and 1e-2, correlation 0.9: the scale spread of Kphi against the Janosi k.
struct CorrelatedGaussian {
  VectorXd mu = (VectorXd(2) << 5e3, 0.3).finished();
  VectorXd sd = (VectorXd(2) << 1e3, 1e-2).finished();
  double rho = 0.9;
  MatrixXd cov() const {
    MatrixXd c(2, 2);
    c << sd[0] * sd[0], rho * sd[0] * sd[1], rho * sd[0] * sd[1], sd[1] * sd[1];
    return c;
  }
  std::vector<Expectation> expectations() const {
    const VectorXd m = mu;
    const MatrixXd c = cov();
    return {{"E x1", [](const VectorXd& x, const VectorXd&) { return x[0]; }, m[0]},
            {"E x2", [](const VectorXd& x, const VectorXd&) { return x[1]; }, m[1]},
            {"Var x1", [m](const VectorXd& x, const VectorXd&) { return (x[0] - m[0]) * (x[0] - m[0]); }, c(0, 0)},
            {"Var x2", [m](const VectorXd& x, const VectorXd&) { return (x[1] - m[1]) * (x[1] - m[1]); }, c(1, 1)},
            {"Cov x1 x2", [m](const VectorXd& x, const VectorXd&) { return (x[0] - m[0]) * (x[1] - m[1]); }, c(0, 1)}};
  }
};

// Haario, Saksman & Tamminen (1999) twisted Gaussian: x ~ N(0, diag(100, 1)) mapped by
// y1 = x1, y2 = x2 - b x1^2 + 100 b (Jacobian 1), so log pi(y) = -y1^2/200 - (y2 + b y1^2 - 100 b)^2 / 2.
//   y1 ~ N(0, 100): E y1 = 0, Var y1 = 100.
//   y2 | y1 ~ N(100 b - b y1^2, 1): E y2 = 100 b - b E y1^2 = 0;
//   Var y2 = E Var(y2|y1) + Var E(y2|y1) = 1 + b^2 Var(y1^2) = 1 + b^2 * 2 * 100^2 = 1 + 2e4 b^2 (19 for b = 0.03);
//   Cov(y1, y2) = -b E y1^3 = 0;
//   E y1^2 y2 = 100 b E y1^2 - b E y1^4 = 100 b * 100 - b * 3 * 100^2 = -2e4 b (-600): the twist itself.
struct Banana {
  double b = 0.03;
  Target target() const {
    Target t;
    t.dim = 2;
    t.log_density = [b = b](const VectorXd& y, const VectorXd&) {
      const double u = y[1] + b * y[0] * y[0] - 100 * b;
      return -y[0] * y[0] / 200 - 0.5 * u * u;
    };
    return t;
  }
  std::vector<Expectation> expectations() const {
    return {{"E y1", [](const VectorXd& y, const VectorXd&) { return y[0]; }, 0.0},
            {"E y2", [](const VectorXd& y, const VectorXd&) { return y[1]; }, 0.0},
            {"Var y1", [](const VectorXd& y, const VectorXd&) { return y[0] * y[0]; }, 100.0},
            {"Var y2", [](const VectorXd& y, const VectorXd&) { return y[1] * y[1]; }, 1 + 2e4 * b * b},
            {"Cov y1 y2", [](const VectorXd& y, const VectorXd&) { return y[0] * y[1]; }, 0.0},
            {"E y1^2 y2", [](const VectorXd& y, const VectorXd&) { return y[0] * y[0] * y[1]; }, -2e4 * b}};
  }
};

// Data y_i ~ N(mu, s2), prior mu | s2 ~ N(m0, s2 / k0), s2 ~ InvGamma(a0, b0). The sampler sees
// mu as x and s2 as the nuisance, drawn by Gibbs from
//   s2 | mu, y ~ InvGamma(a0 + (n+1)/2, b0 + (sum (y_i - mu)^2 + k0 (mu - m0)^2) / 2).
// Posterior (Normal-inverse-gamma; Gelman et al., BDA3 section 3.3):
//   kn = k0 + n, mn = (k0 m0 + n ybar) / kn, an = a0 + n/2,
//   bn = b0 + sum (y_i - ybar)^2 / 2 + k0 n (ybar - m0)^2 / (2 kn);
//   mu | y ~ t_{2 an}(mn, bn / (an kn)): E mu = mn, Var mu = bn / ((an - 1) kn); E s2 = bn / (an - 1).
struct NormalInverseGamma {
  std::vector<double> y;
  double m0 = 0, k0 = 0.5, a0 = 3, b0 = 1;
  NormalInverseGamma() {
    Rng rng(2024);
    for (int i = 0; i < 10; ++i) y.push_back(2.0 + 0.5 * rng.normal());
  }
  double sum_sq(double mu) const {
    double s = k0 * (mu - m0) * (mu - m0);
    for (double v : y) s += (v - mu) * (v - mu);
    return s;
  }
  Target target() const {
    Target t;
    t.dim = 1;
    t.nuisance_dim = 1;
    t.log_density = [this](const VectorXd& x, const VectorXd& s2) { return -0.5 * sum_sq(x[0]) / s2[0]; };
    t.gibbs = [this](const VectorXd& x, VectorXd& s2, Rng& rng) {
      s2[0] = (b0 + 0.5 * sum_sq(x[0])) / rng.gamma(a0 + 0.5 * (y.size() + 1));  // 1/Gamma(a, 1) * scale
    };
    return t;
  }
  std::vector<Expectation> expectations() const {
    const double n = double(y.size());
    double ybar = 0, ss = 0;
    for (double v : y) ybar += v / n;
    for (double v : y) ss += (v - ybar) * (v - ybar);
    const double kn = k0 + n, mn = (k0 * m0 + n * ybar) / kn, an = a0 + n / 2;
    const double bn = b0 + ss / 2 + k0 * n * (ybar - m0) * (ybar - m0) / (2 * kn);
    return {{"E mu", [](const VectorXd& x, const VectorXd&) { return x[0]; }, mn},
            {"Var mu", [mn](const VectorXd& x, const VectorXd&) { return (x[0] - mn) * (x[0] - mn); },
             bn / ((an - 1) * kn)},
            {"E s2", [](const VectorXd&, const VectorXd& s2) { return s2[0]; }, bn / (an - 1)}};
  }
};

// Standard normal in 2-D whose log density is NaN for x1 > 1 and throws for x2 < -0.5: the chain
// samples the normal truncated to x1 <= 1, x2 >= -0.5, whose means are
//   E x1 = -phi(1) / Phi(1) = -0.28760,   E x2 = phi(0.5) / Phi(0.5) = 0.50916.
struct BrokenGaussian {
  Target target() const {
    Target t;
    t.dim = 2;
    t.log_density = [](const VectorXd& x, const VectorXd&) {
      if (x[1] < -0.5) throw std::runtime_error("forward model failed");
      return x[0] > 1 ? std::nan("") : -0.5 * x.squaredNorm();
    };
    return t;
  }
  static double phi(double x) { return std::exp(-0.5 * x * x) / std::sqrt(2 * std::numbers::pi); }
  static double Phi(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }
  std::vector<Expectation> expectations() const {
    return {{"E x1", [](const VectorXd& x, const VectorXd&) { return x[0]; }, -phi(1) / Phi(1)},
            {"E x2", [](const VectorXd& x, const VectorXd&) { return x[1]; }, phi(0.5) / Phi(0.5)}};
  }
};

VectorXd vec(std::initializer_list<double> v) {
  VectorXd out(v.size());
  std::size_t i = 0;
  for (double e : v) out[i++] = e;
  return out;
}

}  // namespace

// --- DRAM -----------------------------------------------------------------------------------

TEST_CASE("DRAM: correlated Gaussian with scales 1e3 and 1e-2", "[samplers][dram]") {
  const CorrelatedGaussian g;
  const Target t = gaussian(g.mu, g.cov());
  // Start 2 sd away, proposal 10x too small and uncorrelated: adaptation must find the shape.
  const VectorXd x0 = g.mu + vec({2e3, -2e-2});
  const MatrixXd cov0 = vec({1e2 * 1e2, 1e-3 * 1e-3}).asDiagonal();
  const DramRun run = run_dram(t, g.expectations(), x0, VectorXd(), cov0, DramOptions{}, 20000, 20000, 1);
  check_expectations(g.expectations(), run.values, 3000);

  // AM learns s_d * Sigma (Haario et al. 2001): the adapted correlation and scales are the target's.
  const double sd = 2.38 * 2.38 / 2;
  const MatrixXd c = run.chains[0].proposal_covariance() / sd;
  CHECK(c(0, 1) / std::sqrt(c(0, 0) * c(1, 1)) == Approx(0.9).margin(0.03));
  CHECK(std::sqrt(c(0, 0)) == Approx(1e3).epsilon(0.15));
  CHECK(std::sqrt(c(1, 1)) == Approx(1e-2).epsilon(0.15));
  CHECK(run.chains[0].stats().acceptance_rate() > 0.2);
}

TEST_CASE("DRAM: Haario's twisted Gaussian (banana)", "[samplers][dram]") {
  const Banana banana;
  const Target t = banana.target();
  const DramRun run = run_dram(t, banana.expectations(), vec({5, 5}), VectorXd(), MatrixXd::Identity(2, 2),
                               DramOptions{}, 5000, 60000, 2);
  check_expectations(banana.expectations(), run.values, 300);
}

TEST_CASE("DRAM: the second-stage acceptance keeps a skewed target exact", "[samplers][dram]") {
  // Gamma(3, 1) on x > 0 (-inf outside): mean 3, variance 3, P(x < 1) = 1 - 5/(2e). Stage 2 draws
  // from the same proposal as stage 1 (dr_scale = 1), where the q1(y2 -> y1) / q1(x -> y1) ratio and
  // the (1 - alpha1) factors of alpha2 are far from 1: leaving out either biases the mean by > 5 MCSE
  // (checked by mutation), which a much narrower second stage would hide.
  Target t;
  t.dim = 1;
  t.log_density = [](const VectorXd& x, const VectorXd&) {
    return x[0] > 0 ? 2 * std::log(x[0]) - x[0] : -std::numeric_limits<double>::infinity();
  };
  const std::vector<Expectation> es = {
      {"E x", [](const VectorXd& x, const VectorXd&) { return x[0]; }, 3.0},
      {"Var x", [](const VectorXd& x, const VectorXd&) { return (x[0] - 3) * (x[0] - 3); }, 3.0},
      {"P(x < 1)", [](const VectorXd& x, const VectorXd&) { return x[0] < 1 ? 1.0 : 0.0; }, 1 - 2.5 * std::exp(-1.0)}};
  DramOptions opt;
  opt.dr_scale = 1.0;
  const DramRun run = run_dram(t, es, vec({3}), VectorXd(), MatrixXd::Constant(1, 1, 1.0), opt, 0, 50000, 3);
  check_expectations(es, run.values, 3000);
}

TEST_CASE("DRAM: Gibbs on the noise variance gives the Normal-inverse-gamma posterior", "[samplers][dram]") {
  const NormalInverseGamma nig;
  const Target t = nig.target();
  const DramRun run =
      run_dram(t, nig.expectations(), vec({0}), vec({1}), MatrixXd::Constant(1, 1, 0.1), DramOptions{}, 2000, 20000, 4);
  check_expectations(nig.expectations(), run.values, 3000);
}

TEST_CASE("DRAM: failed evaluations are rejected and counted, the truncated target is sampled", "[samplers][dram]") {
  const BrokenGaussian broken;
  const Target t = broken.target();
  const DramRun run = run_dram(t, broken.expectations(), vec({0, 0}), VectorXd(), MatrixXd::Identity(2, 2),
                               DramOptions{}, 2000, 20000, 5);
  check_expectations(broken.expectations(), run.values, 3000);
  for (const auto& chain : run.chains) {
    CHECK(chain.stats().iterations == 22000);
    CHECK(chain.stats().failed_evaluations > 1000);
  }
}

TEST_CASE("DRAM: a checkpoint continues with bit-identical draws", "[samplers][dram]") {
  const NormalInverseGamma nig;  // with a nuisance, so the Gibbs state is checkpointed too
  const Target t = nig.target();
  DramOptions opt;
  opt.adapt_start = 100;  // adaptation running at the checkpoint: its state must be saved
  DramChain chain(t, opt, vec({0}), vec({1}), MatrixXd::Constant(1, 1, 0.1), Rng(77));
  for (int i = 0; i < 500; ++i) chain.step(true);
  const std::string saved = chain.save().dump();  // through text: doubles must round-trip exactly

  auto record = [](DramChain& c) {
    std::vector<double> d;
    for (int i = 0; i < 500; ++i) {
      c.step(true);
      d.insert(d.end(), {c.x()[0], c.nuisance()[0], c.log_density(), c.proposal_covariance()(0, 0)});
    }
    return d;
  };
  const std::vector<double> d1 = record(chain);
  DramChain fresh(t, DramOptions{.adapt_start = 100}, vec({1}), vec({2}), MatrixXd::Constant(1, 1, 3), Rng(5));
  fresh.load(nlohmann::json::parse(saved));
  const std::vector<double> d2 = record(fresh);
  REQUIRE(d1.size() == d2.size());
  CHECK(d1 == d2);
  CHECK(fresh.save() == chain.save());
  CHECK(fresh.stats().iterations == 1000);
}

TEST_CASE("DRAM: invalid set-ups are rejected", "[samplers][dram]") {
  const BrokenGaussian broken;
  const Target t = broken.target();
  const MatrixXd eye = MatrixXd::Identity(2, 2);
  CHECK_THROWS_AS(DramChain(t, {}, vec({2, 0}), VectorXd(), eye, Rng(1)), std::invalid_argument);   // NaN
  CHECK_THROWS_AS(DramChain(t, {}, vec({0, -1}), VectorXd(), eye, Rng(1)), std::invalid_argument);  // throws
  CHECK_THROWS_AS(DramChain(t, {}, vec({0}), VectorXd(), eye, Rng(1)), std::invalid_argument);      // size
  CHECK_THROWS_AS(DramChain(t, {}, vec({0, 0}), VectorXd(), -eye, Rng(1)), std::invalid_argument);  // not PD
  DramChain ok(t, {}, vec({0, 0}), VectorXd(), eye, Rng(1));
  nlohmann::json bad = ok.save();
  bad["x"] = {1.0};
  CHECK_THROWS(ok.load(bad));
  CHECK(ok.x() == vec({0, 0}));  // a rejected checkpoint leaves the chain unchanged
}

// --- ensemble -------------------------------------------------------------------------------

TEST_CASE("ensemble: correlated Gaussian with scales 1e3 and 1e-2", "[samplers][ensemble]") {
  const CorrelatedGaussian g;
  const Target t = gaussian(g.mu, g.cov());
  const EnsembleRun run =
      run_ensemble(t, g.expectations(), g.mu + vec({2e3, -2e-2}), vec({10, 1e-4}), VectorXd(), 16, 2000, 10000, 6);
  check_expectations(g.expectations(), run.values, 400);
}

TEST_CASE("ensemble: Haario's twisted Gaussian (banana)", "[samplers][ensemble]") {
  const Banana banana;
  const Target t = banana.target();
  const EnsembleRun run =
      run_ensemble(t, banana.expectations(), vec({5, 5}), vec({0.1, 0.1}), VectorXd(), 32, 2000, 20000, 7);
  // The stretch move crawls along the curved arms (tau ~ 10^3 steps for y2^2): a lower ESS floor.
  check_expectations(banana.expectations(), run.values, 50);
}

TEST_CASE("ensemble: per-walker Gibbs on the noise variance gives the Normal-inverse-gamma posterior",
          "[samplers][ensemble]") {
  const NormalInverseGamma nig;
  const Target t = nig.target();
  const EnsembleRun run = run_ensemble(t, nig.expectations(), vec({0}), vec({0.1}), vec({1}), 8, 1000, 10000, 8);
  check_expectations(nig.expectations(), run.values, 1000);
}

TEST_CASE("ensemble: failed evaluations are rejected and counted, the truncated target is sampled",
          "[samplers][ensemble]") {
  const BrokenGaussian broken;
  const Target t = broken.target();
  const EnsembleRun run =
      run_ensemble(t, broken.expectations(), vec({0, 0}), vec({0.1, 0.1}), VectorXd(), 8, 1000, 10000, 9);
  check_expectations(broken.expectations(), run.values, 400);
  for (const auto& s : run.samplers)
    for (const auto& st : s.stats()) {
      CHECK(st.iterations == 11000);
      CHECK(st.failed_evaluations > 100);
    }
}

TEST_CASE("ensemble: a checkpoint continues with bit-identical draws", "[samplers][ensemble]") {
  const NormalInverseGamma nig;
  const Target t = nig.target();
  auto make = [&](double x0, std::uint64_t seed) {
    std::vector<VectorXd> w, n;
    for (int k = 0; k < 6; ++k) w.push_back(vec({x0 + 0.1 * k})), n.push_back(vec({1.0 + k}));
    return EnsembleSampler(t, {}, w, n, Rng(seed));
  };
  EnsembleSampler s = make(0, 77);
  for (int i = 0; i < 500; ++i) s.step();
  const std::string saved = s.save().dump();
  auto record = [](EnsembleSampler& e) {
    std::vector<double> d;
    for (int i = 0; i < 500; ++i) {
      e.step();
      for (std::size_t k = 0; k < e.size(); ++k)
        d.insert(d.end(), {e.walkers()[k][0], e.nuisances()[k][0], e.log_densities()[k]});
    }
    return d;
  };
  const std::vector<double> d1 = record(s);
  EnsembleSampler fresh = make(1, 5);
  fresh.load(nlohmann::json::parse(saved));
  const std::vector<double> d2 = record(fresh);
  CHECK(d1 == d2);
  CHECK(fresh.save() == s.save());
}

TEST_CASE("ensemble: invalid set-ups are rejected", "[samplers][ensemble]") {
  const BrokenGaussian broken;
  const Target t = broken.target();
  auto walkers = [](int n, double x1) { return std::vector<VectorXd>(n, vec({0, x1})); };
  CHECK_THROWS_AS(EnsembleSampler(t, {}, walkers(3, 0), {}, Rng(1)), std::invalid_argument);     // fewer than 2*dim
  CHECK_THROWS_AS(EnsembleSampler(t, {}, walkers(5, 0), {}, Rng(1)), std::invalid_argument);     // odd
  CHECK_THROWS_AS(EnsembleSampler(t, {}, walkers(4, -1), {}, Rng(1)), std::invalid_argument);    // throws
  CHECK_THROWS_AS(EnsembleSampler(t, {1.0}, walkers(4, 0), {}, Rng(1)), std::invalid_argument);  // a <= 1
  CHECK_NOTHROW(EnsembleSampler(t, {}, walkers(4, 0), {}, Rng(1)));
}

// --- checkpoint encoding ----------------------------------------------------------------------

TEST_CASE("checkpoint JSON: doubles round-trip bit for bit, infinities included", "[samplers]") {
  const VectorXd v = vec({0.1 + 0.2, 1.0 / 3.0, 4.9e-324, 1.7976931348623157e308, -2.5e-310, std::nextafter(1.0, 2.0),
                          -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()});
  const VectorXd back = vector_from_json(nlohmann::json::parse(vector_to_json(v).dump()), v.size());
  for (Eigen::Index i = 0; i < v.size(); ++i) CHECK(back[i] == v[i]);
  CHECK(std::isnan(decode_double(nlohmann::json::parse(encode_double(std::nan("")).dump()))));
}
