// Adaptive importance sampling of the independence proposal (bayes/proposal_adaptation) and the
// unbounded coordinates of a box (bayes/box_transform), on textbook targets with closed forms.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include "bayes/box_transform.hpp"
#include "bayes/calibrator.hpp"
#include "bayes/proposal_adaptation.hpp"

using namespace terracal::bayes;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using terracal::Rng;

namespace {

// A correlated 3-D Gaussian N(mu, S), as a batch target without nuisance.
struct Gaussian3 {
  VectorXd mu = (VectorXd(3) << 1.0, -2.0, 0.5).finished();
  MatrixXd S = (MatrixXd(3, 3) << 1.0, 0.6, 0.0, 0.6, 2.0, -0.5, 0.0, -0.5, 0.5).finished();
  Target target() const {
    Target t;
    t.dim = 3;
    const Eigen::LLT<MatrixXd> llt(S);
    t.log_density = [mu = mu, llt](const VectorXd& x, const VectorXd&) {
      return -0.5 * (llt.matrixL().solve(x - mu)).squaredNorm();
    };
    t.log_density_batch = [f = t.log_density](const std::vector<VectorXd>& xs, const std::vector<VectorXd>& ns,
                                               std::vector<double>& out) {
      out.resize(xs.size());
      for (std::size_t i = 0; i < xs.size(); ++i) out[i] = f(xs[i], ns[i]);
    };
    return t;
  }
};

// Adaptation on g from a proposal 8 sd off and 10 times too narrow.
AdaptedProposal adapt_from_off_start(const Gaussian3& g, const ProposalAdaptationOptions& o, std::uint64_t seed) {
  const VectorXd start = g.mu + 8.0 * g.S.diagonal().cwiseSqrt();
  const MatrixXd narrow = 0.01 * MatrixXd::Identity(3, 3);
  Rng rng(seed);
  return adapt_proposal(g.target(), start, narrow, VectorXd(), o, rng);
}

// Moments of a weighted sample of effective size ESS: the mean within 3 standard errors
// (sd / sqrt(ESS)), the variance within 3 of its relative standard error sqrt(2 / ESS).
void check_moments(const Gaussian3& g, const AdaptedProposal& a) {
  for (int j = 0; j < 3; ++j) {
    CHECK(std::abs(a.mean[j] - g.mu[j]) < 3 * std::sqrt(g.S(j, j) / a.ess));
    CHECK(a.covariance(j, j) == Approx(g.S(j, j)).epsilon(3 * std::sqrt(2 / a.ess)));
  }
}

}  // namespace

TEST_CASE("proposal adaptation: effective sample size and the tempering exponent", "[bayes][adaptation]") {
  CHECK(effective_sample_size(std::vector<double>(10, 3.0), 1.0) == Approx(10.0));
  // One weight of e^0 and nine of e^-inf: one point carries everything.
  std::vector<double> one(10, -std::numeric_limits<double>::infinity());
  one[4] = 0;
  CHECK(effective_sample_size(one, 1.0) == Approx(1.0));
  CHECK(effective_sample_size(one, 0.3) == Approx(1.0));  // -inf stays zero weight at any beta
  // Uneven weights: beta = 0 makes them equal, beta = 1 keeps them; in between the ESS is the target.
  std::vector<double> lw;
  for (int i = 0; i < 100; ++i) lw.push_back(0.2 * i);
  const double ess1 = effective_sample_size(lw, 1.0);
  REQUIRE(ess1 < 20);
  CHECK(tempering_exponent(lw, ess1 / 2) == 1.0);
  const double beta = tempering_exponent(lw, 50);
  CHECK(beta > 0);
  CHECK(beta < 1);
  CHECK(effective_sample_size(lw, beta) == Approx(50).epsilon(1e-6));
}

TEST_CASE("proposal adaptation: a proposal 8 sd off and 10 times too narrow moves onto a Gaussian target",
          "[bayes][adaptation]") {
  const Gaussian3 g;
  const AdaptedProposal a = adapt_from_off_start(g, ProposalAdaptationOptions{}, 7);
  INFO("rounds " << a.rounds << ", beta " << a.beta << ", ESS " << a.ess << "\nmean " << a.mean.transpose()
                 << "\ncovariance\n"
                 << a.covariance);
  REQUIRE(a.reached_posterior);
  CHECK(a.beta == 1.0);
  CHECK(a.rounds > 1);  // the first round's weights were too uneven: it had to temper
  check_moments(g, a);
  CHECK(a.covariance(0, 1) / std::sqrt(a.covariance(0, 0) * a.covariance(1, 1)) ==
        Approx(0.6 / std::sqrt(2.0)).margin(0.15));
}

TEST_CASE("proposal adaptation: rounds at the posterior's weights go on until the final ESS is reached",
          "[bayes][adaptation]") {
  // From the same off, narrow start: the default ends at the first round at beta = 1, which keeps
  // the tempering target (a fifth of a round's points); with final_ess the rounds go on at beta = 1
  // until the weights of all rounds hold that many effective points, and the moments it fits are
  // then within the tighter standard errors that effective size gives.
  const Gaussian3 g;
  ProposalAdaptationOptions o;
  o.max_rounds = 30;
  const AdaptedProposal first = adapt_from_off_start(g, o, 7);
  o.final_ess = 400;
  const AdaptedProposal more = adapt_from_off_start(g, o, 7);
  INFO("first: " << first.rounds << " rounds, ESS " << first.ess << "; with final_ess: " << more.rounds
                 << " rounds, ESS " << more.ess);
  REQUIRE(first.reached_posterior);
  REQUIRE(more.reached_posterior);
  REQUIRE(first.ess < o.final_ess);  // the premise: the default stops short of it
  CHECK(more.beta == 1.0);
  CHECK(more.ess >= o.final_ess);
  CHECK(more.rounds > first.rounds);
  CHECK(more.rounds < o.max_rounds);
  check_moments(g, more);
}

TEST_CASE("proposal adaptation: failed points get no weight", "[bayes][adaptation]") {
  const Gaussian3 g;
  Target t = g.target();
  // Every point with x0 above the mean fails: the fitted mean moves below the true one, by the
  // half-normal's mean sqrt(2/pi) sd, exactly what the successful points say.
  const auto base = t.log_density_batch;
  t.log_density_batch = [base, mu0 = g.mu[0]](const std::vector<VectorXd>& xs, const std::vector<VectorXd>& ns,
                                              std::vector<double>& out) {
    base(xs, ns, out);
    for (std::size_t i = 0; i < xs.size(); ++i)
      if (xs[i][0] > mu0) out[i] = std::numeric_limits<double>::quiet_NaN();
  };
  Rng rng(11);
  ProposalAdaptationOptions o;
  o.max_rounds = 20;
  const AdaptedProposal a = adapt_proposal(t, g.mu, g.S, VectorXd(), o, rng);
  REQUIRE(a.reached_posterior);
  CHECK(a.mean[0] == Approx(g.mu[0] - std::sqrt(2.0 / M_PI)).margin(0.15));
}

TEST_CASE("box transform: round trip, Jacobian and a covariance carried to u", "[bayes][box]") {
  const BoxTransform box((VectorXd(2) << 2.0, -1.0).finished(), (VectorXd(2) << 5.0, 1.0).finished());
  const VectorXd x = (VectorXd(2) << 4.4, -0.95).finished();
  const VectorXd u = box.to_u(x);
  CHECK((box.to_x(u) - x).norm() < 1e-12);
  // log |dx/du| against central differences of to_x.
  double numeric = 0;
  for (int j = 0; j < 2; ++j) {
    VectorXd a = u, b = u;
    a[j] -= 1e-6;
    b[j] += 1e-6;
    numeric += std::log((box.to_x(b)[j] - box.to_x(a)[j]) / 2e-6);
  }
  CHECK(box.log_jacobian(u) == Approx(numeric).epsilon(1e-7));
  CHECK(std::isfinite(box.log_jacobian((VectorXd(2) << 800.0, -800.0).finished())));
  // A point on a bound maps inside; far beyond stays finite.
  CHECK(std::isfinite(box.to_u((VectorXd(2) << 2.0, 1.0).finished()).norm()));
  const MatrixXd cu = box.covariance_to_u(u, 1e-4 * MatrixXd::Identity(2, 2));
  const VectorXd d = box.dx_du(u);
  CHECK(cu(0, 0) == Approx(1e-4 / (d[0] * d[0])));
  CHECK_THROWS(BoxTransform((VectorXd(1) << 1.0).finished(), (VectorXd(1) << 1.0).finished()));
}

TEST_CASE("box transform: independence chains sample a density pressed against its bound exactly",
          "[bayes][box]") {
  // On [2, 5] x [-1, 1]: x0 uniform (mean 3.5, sd sqrt(0.75)); x1 with density (1 + x1)^3 / 4, which
  // leans on its upper bound (y = 1 + x1 on [0, 2] has density y^3 / 4: mean 1.6, E y^2 = 8/3).
  Target t;
  t.dim = 2;
  t.lower = (VectorXd(2) << 2.0, -1.0).finished();
  t.upper = (VectorXd(2) << 5.0, 1.0).finished();
  t.log_density = [lo = t.lower, hi = t.upper](const VectorXd& x, const VectorXd&) {
    for (int j = 0; j < 2; ++j)
      if (x[j] < lo[j] || x[j] > hi[j]) return -std::numeric_limits<double>::infinity();
    return 3.0 * std::log(1.0 + x[1]);
  };
  CalibrationResult res;
  res.point.x = (VectorXd(2) << 3.5, 0.8).finished();
  res.point.covariance = (VectorXd(2) << 0.5, 0.02).finished().asDiagonal();
  res.point.noise_var = VectorXd();
  res.names = {"x0", "x1"};
  res.num_params = 2;
  CalibrationOptions opt;
  opt.seed = 5;
  opt.chains = 8;
  opt.sampler = SamplerKind::kIndependence;
  opt.min_ess = 1000;
  opt.warmup = 50;
  opt.block = 200;
  opt.max_draws = 20000;
  sample_posterior(t, opt, res);
  INFO(res.termination);
  REQUIRE(res.converged);
  const double mean[2] = {3.5, 0.6}, sd[2] = {std::sqrt(0.75), std::sqrt(8.0 / 3.0 - 1.6 * 1.6)};
  for (int v = 0; v < 2; ++v) {
    const VariableSummary& s = res.summary[v];
    const double mcse = s.sd / std::sqrt(s.ess_bulk);
    INFO(res.names[v] << ": mean " << s.mean << " (exact " << mean[v] << ", MCSE " << mcse << "), sd " << s.sd
                      << " (exact " << sd[v] << ")");
    CHECK(std::abs(s.mean - mean[v]) < 4 * mcse);
    CHECK(s.sd == Approx(sd[v]).epsilon(0.08));
    CHECK(s.q05 >= t.lower[v]);
    CHECK(s.q95 <= t.upper[v]);
  }
}
