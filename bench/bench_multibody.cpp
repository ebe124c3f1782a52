// The multibody integrator's accuracy against its cost: the crank-rocker four-bar of the tests
// (3 bodies, 16 joint rows, a conservative system) over 20 s simulated, at IDAS tolerances from 1e-4 to
// 1e-10: wall time (median of repeats), IDAS steps, residual and Jacobian evaluations, the largest
// constraint error and the largest relative energy change over the run (sampled every 0.01 s).
// Usage: bench_multibody [repeats=3]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "bench/bench_stats.hpp"
#include "highfi/multibody/mb_integrator.hpp"
#include "tests/highfi/multibody/mb_test_systems.hpp"

using namespace terracal;
using namespace terracal::mb;

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::atoi(argv[1]) : 3;
  const double simulated = 20.0;
  std::printf("four-bar, %.0f s simulated, one core\n", simulated);
  std::printf("%8s %10s %10s %8s %10s %8s %12s %12s\n", "rtol", "wall_s", "x_realtime", "steps", "residuals",
              "jacobians", "max_constr", "max_dE_rel");
  for (double rtol : {1e-4, 1e-6, 1e-8, 1e-10}) {
    std::vector<double> walls;
    MbIntegratorStats st;
    double violation = 0, drift = 0;
    for (int r = 0; r < repeats; ++r) {
      MbSystem s;
      test::four_bar(s);
      const auto start = std::chrono::steady_clock::now();
      MbIntegrator in(s, {rtol, rtol * 1e-2});
      const double e0 = s.mechanical_energy();
      violation = drift = 0;
      for (int k = 1; k <= int(simulated * 100); ++k) {
        in.advance(k * 0.01);
        violation = std::max(violation, in.constraint_violation());
        drift = std::max(drift, std::abs(s.mechanical_energy() - e0) / std::abs(e0));
      }
      walls.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      st = in.stats();
    }
    const double wall = bench::median(walls);
    std::printf("%8.0e %10.3f %10.1f %8ld %10ld %8ld %12.2e %12.2e\n", rtol, wall, simulated / wall, st.steps,
                st.residuals, st.jacobians, violation, drift);
  }
  return 0;
}
