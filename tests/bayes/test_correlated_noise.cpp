// Correlated residuals in the simulation-backed calibration problem (bayes/model_problem): the
// correlation time estimated from the residuals, and a likelihood that counts N / tau rows, against
// closed forms on a one-parameter model y = a + noise.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <vector>

#include "bayes/model_problem.hpp"
#include "core/errors.hpp"

using namespace terracal::bayes;
using Eigen::VectorXd;
using terracal::InputError;
using terracal::Rng;

namespace {

constexpr double kLevel = 2.0;

// Four references of `rows` rows each of kLevel + AR(1) noise (lag-one correlation rho, sd 0.1).
ModelChannel ar1_channel(double rho, int rows, std::uint64_t seed) {
  ModelChannel ch{"vx", "m/s", {}, {}, {}, {"r0", "r1", "r2", "r3"}};
  Rng rng(seed);
  for (int k = 0; k < 4; ++k) {
    double e = 0.1 * rng.normal();
    for (int i = 0; i < rows; ++i) {
      ch.y.push_back(kLevel + e);
      ch.x.push_back(0.01 * i);
      ch.curve.push_back(k);
      e = rho * e + 0.1 * std::sqrt(1 - rho * rho) * rng.normal();
    }
  }
  return ch;
}

ModelProblem level_problem(const ModelChannel& ch) {
  Prior p;
  p.kind = Prior::Kind::kUniform;
  p.lower = 0;
  p.upper = 4;
  const std::size_t n = ch.size();
  return ModelProblem({{"a", "m/s", p, 1.0}}, {ch}, [n](const std::vector<VectorXd>& xs, auto& out) {
    out.assign(xs.size(), std::vector<double>(n, 0.0));
    for (std::size_t i = 0; i < xs.size(); ++i) out[i].assign(n, xs[i][0]);
  });
}

VectorXd one(double v) { return VectorXd::Constant(1, v); }

}  // namespace

TEST_CASE("correlated noise: the correlation time of AR(1) residuals is (1 + rho) / (1 - rho)",
          "[bayes][model_problem][noise]") {
  for (const double rho : {0.0, 0.5, 0.9}) {
    const ModelProblem pb = level_problem(ar1_channel(rho, 2000, 17));
    const double tau = pb.correlation_times(one(kLevel))[0];
    INFO("rho " << rho << ": tau " << tau);
    CHECK(tau == Approx(std::max(1.0, (1 + rho) / (1 - rho))).epsilon(rho > 0 ? 0.15 : 0.0).margin(rho > 0 ? 0 : 0.1));
  }
  // Residuals that never change (a constant offset) are one row's worth per ten: tau hits N / 10.
  const ModelProblem flat = level_problem(ar1_channel(1.0, 500, 3));
  CHECK(flat.correlation_times(one(kLevel + 1.0))[0] == Approx(200.0));
}

TEST_CASE("correlated noise: the marginal density is the joint one integrated over the noise variance",
          "[bayes][model_problem][noise]") {
  ModelProblem pb = level_problem(ar1_channel(0.5, 100, 5));
  pb.set_correlation_times(one(4.0));
  CHECK(pb.effective_rows(0) == Approx(100.0));
  const Target t = pb.target();
  // log of the integral over s^2 of exp(log_posterior), on a fine grid of log s^2 (ds^2 = s^2 dlog s^2).
  const auto integrated = [&](double a) {
    const VectorXd sse = pb.sse({one(a)})[0];
    double top = -1e300;
    std::vector<double> v;
    for (double l = -12; l <= 4; l += 1e-3) {
      v.push_back(pb.log_posterior(one(a), sse, one(std::exp(l))) + l);
      top = std::max(top, v.back());
    }
    double s = 0;
    for (double e : v) s += std::exp(e - top);
    return top + std::log(s * 1e-3);
  };
  std::vector<double> lm;
  t.log_marginal_batch({one(1.98), one(2.05)}, lm);
  CHECK(lm[0] - lm[1] == Approx(integrated(1.98) - integrated(2.05)).epsilon(1e-6));
}

TEST_CASE("correlated noise: the Gibbs step draws s^2 from inverse-gamma(N / 2 tau, SSE / 2 tau)",
          "[bayes][model_problem][noise]") {
  ModelProblem pb = level_problem(ar1_channel(0.0, 50, 9));
  const double tau = 5;
  pb.set_correlation_times(one(tau));
  const Target t = pb.target();
  const double sse = pb.sse({one(kLevel)})[0][0];
  Rng rng(2);
  double sum = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    VectorXd nv = one(1.0);
    t.gibbs(one(kLevel), nv, rng);
    sum += nv[0];
  }
  // The mean of inverse-gamma(alpha, beta) is beta / (alpha - 1) = SSE / (N - 2 tau); with tau = 1 it
  // would be SSE / (N - 2), 1.5 % of what this checks away.
  CHECK(sum / n == Approx(sse / (200.0 - 2 * tau)).epsilon(0.01));
  CHECK_THROWS_AS(pb.set_correlation_times(one(0.5)), InputError);
  CHECK_THROWS_AS(pb.set_correlation_times(VectorXd::Ones(2)), InputError);
}
