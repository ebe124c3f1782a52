// The SCM co-simulation adapter (lowfi/scm_wheels.hpp) as the full vehicle calls it: four HMMWV-sized
// wheels (radius 0.47 m, width 0.25 m; the track 1.8 m, wheelbase 3.4 m) rolling at 5 m/s at slip 0.1,
// held `depth` into dry sand (0.08 m: 4.9 kN a wheel, near the HMMWV's 6.3 kN), effect `damping`, one call of
// step() per 1e-3 s, on one core: wall time per call (the median of repeated runs) after a warm-up second.
// Usage: bench_scm_wheels [repeats=5] [grid=0.02] [steps=2000] [depth=0.08]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <omp.h>

#include "bench/bench_stats.hpp"
#include "lowfi/scm_wheels.hpp"

using namespace terracal;
using Clock = std::chrono::steady_clock;

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::atoi(argv[1]) : 5;
  const double grid = argc > 2 ? std::atof(argv[2]) : 0.02;
  const int steps = argc > 3 ? std::atoi(argv[3]) : 2000;
  const double depth = argc > 4 ? std::atof(argv[4]) : 0.08;
  omp_set_num_threads(1);
  lowfi::ScmSettings s;
  s.grid = grid;
  s.time_step = 1e-3;
  s.effects.enable<lowfi::ScmDamping>();
  const double r = 0.47, b = 0.25, speed = 5.0, slip = 0.1;
  std::vector<lowfi::ScmWheelShape> shapes;
  std::vector<BodyState> states;
  for (int w = 0; w < 4; ++w) {
    shapes.push_back({"wheel " + std::to_string(w), r, b, 0, 0, 0});
    BodyState st;
    st.position = {w < 2 ? 3.4 : 0.0, (w % 2) ? -0.9 : 0.9, r - depth};
    st.velocity = {speed, 0, 0};
    st.omega = {0, speed / (r * (1 - slip)), 0};
    states.push_back(st);
  }
  std::vector<double> per_call;
  double fz = 0, fx = 0;
  for (int rep = 0; rep < repeats; ++rep) {
    lowfi::ScmWheels wheels(lowfi::reference_dry_sand(), s, shapes);
    auto advance = [&] {
      wheels.step(states);
      for (auto& st : states) {
        st.position.x += s.time_step * st.velocity.x;
        st.orientation = integrate_rotation(st.orientation, st.omega, s.time_step);
      }
    };
    for (int k = 0; k < 1000; ++k) advance();  // warm: scratch sized, nodes stored around the wheels
    const auto t0 = Clock::now();
    for (int k = 0; k < steps; ++k) advance();
    per_call.push_back(std::chrono::duration<double>(Clock::now() - t0).count() / steps);
    fz = fx = 0;
    for (const auto& f : wheels.wrenches()) fz += f.force.z, fx += f.force.x;
  }
  std::printf(
      "SCM wheels, 4 wheels %g m deep, grid %g m, step %g s, 1 thread: median %.1f us per step() call (min %.1f, max "
      "%.1f) over "
      "%d runs of %d calls; %.0f x faster than real time for the soil alone\n",
      depth, grid, s.time_step, 1e6 * bench::median(per_call),
      1e6 * *std::min_element(per_call.begin(), per_call.end()),
      1e6 * *std::max_element(per_call.begin(), per_call.end()), repeats, steps, s.time_step / bench::median(per_call));
  std::printf("last wrench sum: Fz %.0f N, Fx %.0f N\n", fz, fx);
  return 0;
}
