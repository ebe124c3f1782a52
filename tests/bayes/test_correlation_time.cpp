// The residual correlation time that tempers a calibration's likelihood (bayes/correlation_time.hpp):
// an AR(1) series' integrated correlation time, the bounds, and what it does to the SCM posterior.
#include <catch2/catch.hpp>

#include <cmath>

#include "bayes/calibration_problem.hpp"
#include "bayes/correlation_time.hpp"
#include "bayes/synthetic_data.hpp"
#include "core/rng.hpp"

using namespace terracal;
using namespace terracal::bayes;

TEST_CASE("the correlation time of an AR(1) series is (1 + rho) / (1 - rho)", "[bayes][correlation]") {
  Rng rng(3);
  for (double rho : {0.0, 0.5, 0.8}) {
    std::vector<double> r(200000);
    std::vector<int> curve(r.size(), 0);
    double x = 0;
    for (double& v : r) v = x = rho * x + rng.normal();
    INFO("rho " << rho);
    CHECK(correlation_time(r, curve) == Approx((1 + rho) / (1 - rho)).epsilon(0.03));
  }
}

TEST_CASE("the correlation time stays within 1 and N / 10 and ignores lags across curves", "[bayes][correlation]") {
  // Alternating signs: negative correlation counts as none.
  std::vector<double> alt{1, -1, 1, -1, 1, -1, 1, -1, 1, -1, 1, -1, 1, -1, 1, -1, 1, -1, 1, -1};
  CHECK(correlation_time(alt, std::vector<int>(alt.size(), 0)) == 1.0);
  // A constant offset (the model misses by the same amount everywhere): capped at N / 10.
  const std::vector<double> offset(50, 2.0);
  CHECK(correlation_time(offset, std::vector<int>(offset.size(), 0)) == 5.0);
  // Each row its own curve: no lag counts, the rows are independent.
  std::vector<int> own(offset.size());
  for (std::size_t i = 0; i < own.size(); ++i) own[i] = static_cast<int>(i);
  CHECK(correlation_time(offset, own) == 1.0);
}

TEST_CASE("a correlation time tempers the SCM likelihood: tau counts N rows as N / tau", "[bayes][correlation]") {
  Rng rng(4);
  const ParamVector truth{990, 1528430, 1.1, 1040, 28, 0.025, 1.5};
  const SyntheticDesign design;
  CalibrationProblem pb(synthesize_plate(truth, design, rng), synthesize_shear(truth, design, rng),
                        default_priors());
  // Synthetic white noise: about no correlation.
  for (double tau : pb.correlation_times(truth)) CHECK(tau < 1.5);
  ParamVector off = truth;
  off[kN] *= 1.02;
  Eigen::VectorXd nv(2);
  nv << 4e-4, 4e-4;
  const double white = pb.log_posterior(truth, nv) - pb.log_posterior(off, nv);
  pb.set_correlation_times({4.0, 4.0});
  CHECK(pb.effective_rows(0) == Approx(pb.set(0).size() / 4.0));
  // The data's term of the log density is divided by tau (the noise terms cancel in the difference).
  CHECK(pb.log_posterior(truth, nv) - pb.log_posterior(off, nv) == Approx(white / 4.0).epsilon(1e-9));
  CHECK_THROWS(pb.set_correlation_times({0.5, 1.0}));
}
