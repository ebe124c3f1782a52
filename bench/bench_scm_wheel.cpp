// The SCM single wheel (radius 0.47 m, width 0.25 m, 108 kg, 1 rad/s, slip 0.3) on
// dry sand at a 0.01 m grid and a 1e-3 s step, on one core: simulated seconds per wall second
// (target >= 20), the median of repeated runs (where the time goes: perf, see RESULTS.md); and the
// steady SCM wheel's wall per slip at the same settings.
// Usage: bench_scm_wheel [repeats=5] [grid=0.01] [duration=5]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <omp.h>

#include "bench/bench_stats.hpp"
#include "lowfi/scm_steady_wheel.hpp"
#include "lowfi/scm_terrain.hpp"
#include "virtual_bevameter/wheel_rig.hpp"

using namespace terracal;
using Clock = std::chrono::steady_clock;

using bench::median;

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::atoi(argv[1]) : 5;
  const double grid = argc > 2 ? std::atof(argv[2]) : 0.01;
  const double duration = argc > 3 ? std::atof(argv[3]) : 5.0;
  omp_set_num_threads(1);
  const lowfi::ScmSoil sand = lowfi::reference_dry_sand();
  lowfi::ScmSettings s;
  s.grid = grid;
  s.time_step = 1e-3;
  s.effects.enable<lowfi::ScmDamping>();
  const lowfi::ScmSite site(sand, s);
  rigs::WheelSpec wheel;
  rigs::WheelRun run;
  run.duration = duration;
  std::vector<double> rates;
  rigs::WheelResult last;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = Clock::now();
    last = rigs::run_wheel(site, wheel, 0.3, run);
    const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
    rates.push_back(duration / wall);
  }
  std::printf(
      "SCM wheel, grid %g m, step %g s, %g s simulated, 1 thread: median %.2f simulated s per wall s (min %.2f, max "
      "%.2f) over %d runs\n",
      grid, s.time_step, duration, median(rates), *std::min_element(rates.begin(), rates.end()),
      *std::max_element(rates.begin(), rates.end()), repeats);
  std::printf("steady: DBP %.1f N, torque %.1f N m, sinkage %.4f m\n", last.dbp, last.torque, last.sinkage);
  // The steady SCM wheel (the calibrator's forward model) at the same slip: wall per evaluation.
  const int evaluations = 200;
  lowfi::WongReeceResult q;
  const auto t0 = Clock::now();
  for (int k = 0; k < evaluations; ++k)
    q = lowfi::scm_steady_wheel(sand, {wheel.radius, wheel.width}, last.load, 0.3 + 1e-9 * k);
  const double each = std::chrono::duration<double>(Clock::now() - t0).count() / evaluations;
  std::printf("steady SCM wheel (quadrature): %.3g s per slip (%d evaluations); DBP %.1f N, torque %.1f N m, "
              "sinkage %.4f m\n",
              each, evaluations, q.dbp, q.torque, q.sinkage);
  return 0;
}
