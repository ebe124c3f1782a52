// Convergence diagnostics against exact small cases, analytic ESS of AR(1) chains, and the
// defining properties of rank normalisation and folding (Vehtari et al. 2021).
#include <catch2/catch.hpp>

#include <cmath>
#include <numeric>
#include <stdexcept>

#include "bayes/diagnostics.hpp"
#include "core/rng.hpp"

using namespace terracal::bayes;
using terracal::Rng;

namespace {

Chains normal_chains(int m, int n, std::uint64_t seed, std::vector<double> mean = {}, std::vector<double> sd = {}) {
  Chains c(m, std::vector<double>(n));
  for (int k = 0; k < m; ++k) {
    Rng rng = Rng::for_stream(seed, k);
    for (double& v : c[k]) v = (mean.empty() ? 0.0 : mean[k]) + (sd.empty() ? 1.0 : sd[k]) * rng.normal();
  }
  return c;
}

// Stationary AR(1), x_t = rho x_{t-1} + sqrt(1 - rho^2) e_t: unit variance, autocorrelation
// rho^t, integrated autocorrelation time (1 + rho) / (1 - rho).
Chains ar1_chains(int m, int n, double rho, std::uint64_t seed) {
  Chains c(m, std::vector<double>(n));
  for (int k = 0; k < m; ++k) {
    Rng rng = Rng::for_stream(seed, k);
    double x = rng.normal();
    for (double& v : c[k]) v = x = rho * x + std::sqrt(1 - rho * rho) * rng.normal();
  }
  return c;
}

}  // namespace

TEST_CASE("diagnostics: classic split R-hat of a hand-computed case", "[diagnostics]") {
  // Halves {1,2} {3,4} {2,3} {4,5}: n = 2, means 1.5 3.5 2.5 4.5, within variances 0.5 -> W = 0.5;
  // variance of the means 5/3 -> B = n * 5/3 = 10/3; R = sqrt((B/W + n - 1) / n) = sqrt(23/6).
  const Chains c = {{1, 2, 3, 4}, {2, 3, 4, 5}};
  CHECK(rhat_split(c) == Approx(std::sqrt(23.0 / 6.0)).epsilon(1e-14));
}

TEST_CASE("diagnostics: summary statistics and type-7 quantiles", "[diagnostics]") {
  Chains c(2, std::vector<double>(50));
  for (int i = 0; i < 100; ++i) c[i / 50][i % 50] = i + 1;  // 1..100
  const VariableSummary s = summarize(c);
  CHECK(s.mean == Approx(50.5));
  CHECK(s.sd == Approx(std::sqrt(100.0 * 101.0 / 12.0)));  // unbiased sd of 1..N: sqrt(N(N+1)/12)
  CHECK(s.q05 == Approx(1 + 0.05 * 99));                   // x[floor(h)] + frac * gap, h = p (N-1)
  CHECK(s.q50 == Approx(50.5));
  CHECK(s.q95 == Approx(1 + 0.95 * 99));
  CHECK(s.rhat > 1.5);  // a trend: both chains' halves differ, the point of splitting
}

TEST_CASE("diagnostics: FFT autocovariance equals the direct sum", "[diagnostics]") {
  Rng rng(11);
  std::vector<double> x(777);  // not a power of two: padding must not wrap around
  for (double& v : x) v = 3.0 + rng.normal() + (v > 0 ? 0.5 : 0.0);
  const double mean = std::accumulate(x.begin(), x.end(), 0.0) / x.size();
  const std::vector<double> acov = autocovariance(x);
  REQUIRE(acov.size() == x.size());
  for (std::size_t t : {0u, 1u, 2u, 50u, 400u, 776u}) {
    double direct = 0;
    for (std::size_t i = 0; i + t < x.size(); ++i) direct += (x[i] - mean) * (x[i + t] - mean);
    CHECK(acov[t] == Approx(direct / x.size()).margin(1e-12));
  }
}

TEST_CASE("diagnostics: R-hat near 1 for independent normal chains", "[diagnostics]") {
  const Chains c = normal_chains(4, 2000, 1);
  CHECK(std::abs(rhat_split(c) - 1.0) < 0.01);
  CHECK(std::abs(rhat_rank(c) - 1.0) < 0.01);
}

TEST_CASE("diagnostics: R-hat detects chains stuck in different modes", "[diagnostics]") {
  const Chains c = normal_chains(4, 2000, 2, {0, 0, 5, 5});
  CHECK(rhat_split(c) > 1.1);
  CHECK(rhat_rank(c) > 1.1);
}

TEST_CASE("diagnostics: folding detects chains that differ only in scale", "[diagnostics]") {
  // Same location, sd 1 vs 3: the classic R-hat compares means and sees nothing; the tail
  // R-hat of |x - median| sees the different spreads.
  const Chains c = normal_chains(4, 2000, 3, {}, {1, 1, 3, 3});
  CHECK(rhat_split(c) < 1.02);
  CHECK(rhat_rank(c) > 1.1);
}

TEST_CASE("diagnostics: rank-normalised statistics are invariant to monotone transforms", "[diagnostics]") {
  const Chains c = ar1_chains(4, 1000, 0.5, 4);
  Chains e = c, a = c;
  for (auto& chain : e)
    for (double& v : chain) v = std::exp(3 * v);  // heavy right tail: same ranks
  for (auto& chain : a)
    for (double& v : chain) v = 7 - 2 * v;  // affine: same ranks of |x - median| too
  CHECK(ess_bulk(e) == ess_bulk(c));
  CHECK(ess_tail(e) == ess_tail(c));
  // Not exact: the two middle draws fold to an exact tie on one side and, after rounding, to
  // two values on the other, which changes their ranks by 1/2.
  CHECK(rhat_rank(a) == Approx(rhat_rank(c)).epsilon(1e-5));
  CHECK(ess_bulk(a) == Approx(ess_bulk(c)).epsilon(1e-12));
}

TEST_CASE("diagnostics: ESS of AR(1) chains matches N (1 - rho) / (1 + rho)", "[diagnostics]") {
  const double rho = 0.9;
  const Chains c = ar1_chains(4, 20000, rho, 5);
  const double expected = 4 * 20000 * (1 - rho) / (1 + rho);  // 4210.5
  CHECK(ess_basic(c) == Approx(expected).epsilon(0.10));
  CHECK(ess_bulk(c) == Approx(expected).epsilon(0.10));  // the ranks of a Gaussian AR(1) ~ same
}

TEST_CASE("diagnostics: ESS of independent draws is the number of draws", "[diagnostics]") {
  const Chains c = normal_chains(4, 2000, 6);
  CHECK(ess_basic(c) == Approx(8000).epsilon(0.10));
  CHECK(ess_bulk(c) == Approx(8000).epsilon(0.10));
  CHECK(ess_tail(c) == Approx(8000).epsilon(0.15));
}

TEST_CASE("diagnostics: constant chains give R-hat 1 and ESS = draws, never NaN", "[diagnostics]") {
  const Chains c(3, std::vector<double>(101, 2.5));
  CHECK(rhat_split(c) == 1.0);
  CHECK(rhat_rank(c) == 1.0);
  CHECK(ess_basic(c) == 303.0);
  CHECK(ess_bulk(c) == 303.0);
  CHECK(ess_tail(c) == 303.0);
  const VariableSummary s = summarize(c);
  for (double v : {s.mean, s.sd, s.q05, s.q50, s.q95, s.rhat, s.ess_bulk, s.ess_tail}) CHECK_FALSE(std::isnan(v));

  // Each chain constant at its own value: infinitely far from converged, still not NaN.
  const Chains stuck = {std::vector<double>(50, 1.0), std::vector<double>(50, 2.0)};
  CHECK(rhat_split(stuck) > 1.1);
  CHECK(rhat_rank(stuck) > 1.1);
  CHECK_FALSE(std::isnan(ess_bulk(stuck)));
  CHECK_FALSE(std::isnan(ess_tail(stuck)));
}

TEST_CASE("diagnostics: malformed input is rejected", "[diagnostics]") {
  CHECK_THROWS_AS(rhat_split(Chains{}), std::invalid_argument);
  CHECK_THROWS_AS(rhat_rank(Chains{{1.0}, {2.0}}), std::invalid_argument);
  CHECK_THROWS_AS(ess_basic(Chains{{1, 2, 3}, {1, 2}}), std::invalid_argument);
  CHECK_THROWS_AS(summarize(Chains{{1, 2}}), std::invalid_argument);  // one chain: nothing to split or compare
  CHECK_THROWS_AS(ess_bulk(Chains{{1, 2}, {2, std::nan("")}}), std::invalid_argument);
  CHECK_NOTHROW(rhat_split(Chains{{1, 2}, {2, 4}}));  // 2 draws per chain: used whole
}

TEST_CASE("diagnostics: bulk ESS of a long AR(1) chain set (4 x 100 000 draws, rho 0.5)", "[diagnostics]") {
  const Chains c = ar1_chains(4, 100000, 0.5, 7);
  const VariableSummary s = summarize(c);  // (exercises the FFT autocovariance at a size where O(N^2) would not do)
  CHECK(s.ess_bulk == Approx(400000.0 / 3.0).epsilon(0.1));
}
