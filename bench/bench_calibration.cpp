// The calibration's speed. Two figures, each the median of repeated runs:
//   1. analytic likelihood evaluations per second on one core (target >= 1e6);
//   2. seconds from curves to a posterior with R-hat < 1.01 and bulk ESS >= 1000 for every
//      parameter (target <= 5 s on the 2-core machine).
// Data: plates of 0.1 and 0.2 m radius with 8 points each; 8 annulus loads (2-20 kPa) with 8
// angles each; 2 % noise; dry sand. Usage: bench_calibration [repeats=5]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <omp.h>

#include "bayes/calibrator.hpp"
#include "bayes/synthetic_data.hpp"
#include "bench/bench_stats.hpp"

using namespace terracal;
using namespace terracal::bayes;
using Clock = std::chrono::steady_clock;

using bench::median;

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::atoi(argv[1]) : 5;
  const ParamVector truth = {990, 1528430, 1.1, 1040, 28, 0.01};
  SyntheticDesign d;
  d.plate_points = 8;
  d.shear_pressures = {2e3, 4.5e3, 7e3, 9.5e3, 12e3, 14.5e3, 17e3, 20e3};
  d.shear_points = 8;
  Rng rng(1);
  const CalibrationProblem problem(synthesize_plate(truth, d, rng), synthesize_shear(truth, d, rng), default_priors());
  std::printf("data: %zu plate points, %zu shear points; %d OpenMP threads\n", problem.set(0).size(),
              problem.set(1).size(), omp_get_max_threads());

  // 1. Likelihood (log posterior) evaluations per second, one core.
  std::vector<double> rates;
  Eigen::VectorXd noise(2);
  noise << 4e-4, 4e-4;
  for (int r = 0; r < repeats; ++r) {
    const int n = 200000;
    ParamVector p = truth;
    double sink = 0;
    const auto t0 = Clock::now();
    for (int i = 0; i < n; ++i) {
      p[kN] = 1.1 + 1e-9 * (i & 7);  // vary the input so nothing is hoisted out of the loop
      sink += problem.log_posterior(p, noise);
    }
    const double s = std::chrono::duration<double>(Clock::now() - t0).count();
    rates.push_back(n / s);
    if (sink == 42) std::puts("");
  }
  std::printf("likelihood: %.3g evaluations/s (median of %d; one core)\n", median(rates), repeats);

  // 2. A whole calibration to R-hat < 1.01 and ESS >= 1000.
  std::vector<double> times;
  for (int r = 0; r < repeats; ++r) {
    CalibrationOptions opt;
    opt.seed = 1 + r;
    opt.min_ess = 1000;
    const auto t0 = Clock::now();
    const CalibrationResult res = calibrate(problem, opt);
    const double s = std::chrono::duration<double>(Clock::now() - t0).count();
    times.push_back(s);
    double max_rhat = 0, min_ess = 1e300;
    for (int v = 0; v < res.num_params; ++v) {
      max_rhat = std::max(max_rhat, res.summary[v].rhat);
      min_ess = std::min(min_ess, res.summary[v].ess_bulk);
    }
    std::printf("  run %d: %.2f s, %s, %ld draws/chain, max R-hat %.4f, min ESS %.0f\n", r, s,
                res.converged ? "converged" : "NOT converged", res.draws, max_rhat, min_ess);
  }
  std::printf("calibration: %.2f s (median of %d)\n", median(times), repeats);
  return 0;
}
