// The reduced-order vehicles' speed on one CPU core: times faster than real time for the HMMWV
// with TMeasy tires at a 1e-3 s half-implicit step over 10 s simulated (LFDM reports 3835x for its
// 18-DOF model on an i7-13700K; our target is >= 10,000x), for each model, both with the stepping
// loop alone and through `run_rom` (which also samples trajectory.csv rows at 100 Hz); CVODES at
// its default tolerances for comparison. Median of repeated runs.
// Usage: bench_rom [repeats=7]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "bench/bench_stats.hpp"
#include "rom/half_implicit.hpp"
#include "rom/rom11.hpp"
#include "rom/rom18.hpp"
#include "rom/rom24.hpp"
#include "rom/rom_run.hpp"
#include "rom/rom_vehicle_json.hpp"

using namespace terracal;
using namespace terracal::rom;
using Clock = std::chrono::steady_clock;

namespace {
constexpr double kSimulated = 10.0, kStep = 1e-3;

// A double lane change-like steering with throttle: every part of the right-hand side is active.
DriverSeries inputs() {
  return DriverSeries::from_rows({0, 2, 3, 4, 5, 6, 10}, {0, 0, 0.2, -0.2, 0.1, 0, 0},
                                 {0.5, 0.5, 0.3, 0.3, 0.5, 0.6, 0.6}, {0, 0, 0, 0, 0, 0, 0}, "bench inputs");
}

template <class M>
double loop_seconds(const RomVehicle& v, const DriverSeries& in) {
  double y[M::kStates];
  int gear = M::initial_state(v, 10.0, y);
  RomAux aux;
  const auto start = Clock::now();
  const long steps = static_cast<long>(kSimulated / kStep);
  for (long k = 0; k < steps; ++k) {
    if (!half_implicit_step<M>(v, in.at(k * kStep), gear, y, kStep, &aux)) std::abort();
  }
  const double s = std::chrono::duration<double>(Clock::now() - start).count();
  if (y[M::kX] < 0) std::puts("");  // keeps the loop's result alive
  return s;
}

double run_seconds(const RomVehicle& v, const DriverSeries& in, RomModel m, RomIntegrator i) {
  RomRunOptions o;
  o.model = m;
  o.integrator = i;
  o.end_time = kSimulated;
  o.initial_speed = 10.0;
  RomDriver d;
  d.series = &in;
  return run_rom(v, d, o).wall_seconds;
}
}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::atoi(argv[1]) : 7;
  const RomVehicle v = load_rom_vehicle("hmmwv");
  const DriverSeries in = inputs();
  std::printf("HMMWV, TMeasy, %.0f s simulated, step %.0e s, one core; median of %d runs\n", kSimulated, kStep,
              repeats);
  std::printf("%-8s %-28s %12s %14s\n", "model", "what", "wall [ms]", "x real time");
  auto report = [&](const char* model, const char* what, auto&& f) {
    std::vector<double> t;
    for (int r = 0; r < repeats; ++r) t.push_back(f());
    const double s = bench::median(t);
    std::printf("%-8s %-28s %12.3f %14.0f\n", model, what, 1e3 * s, kSimulated / s);
  };
  report("11dof", "half-implicit loop", [&] { return loop_seconds<Rom11>(v, in); });
  report("18dof", "half-implicit loop", [&] { return loop_seconds<Rom18>(v, in); });
  report("24dof", "half-implicit loop", [&] { return loop_seconds<Rom24>(v, in); });
  report("11dof", "run_rom half-implicit",
         [&] { return run_seconds(v, in, RomModel::k11Dof, RomIntegrator::kHalfImplicit); });
  report("18dof", "run_rom half-implicit",
         [&] { return run_seconds(v, in, RomModel::k18Dof, RomIntegrator::kHalfImplicit); });
  report("11dof", "run_rom cvodes (1e-6, 1e-8)",
         [&] { return run_seconds(v, in, RomModel::k11Dof, RomIntegrator::kCvodes); });
  report("18dof", "run_rom cvodes (1e-6, 1e-8)",
         [&] { return run_seconds(v, in, RomModel::k18Dof, RomIntegrator::kCvodes); });
  report("24dof", "run_rom half-implicit",
         [&] { return run_seconds(v, in, RomModel::k24Dof, RomIntegrator::kHalfImplicit); });
  report("24dof", "run_rom cvodes (1e-6, 1e-8)",
         [&] { return run_seconds(v, in, RomModel::k24Dof, RomIntegrator::kCvodes); });
  // What each effect costs: the 18-DOF loop with the preset's effects, one of them switched off at a
  // time, and aerodynamic drag switched on. (Without tire_relaxation the tires are steady: a
  // different model, whose loads take a second pass.)
  std::printf("\n18dof half-implicit loop, effects\n");
  const std::pair<const char*, unsigned> toggles[] = {{"preset's effects", 0u},
                                                      {"- tire_relaxation", kEffectTireRelaxation},
                                                      {"- torque_converter", kEffectTorqueConverter},
                                                      {"- roll", kEffectRoll},
                                                      {"- rolling_resistance", kEffectRollingResistance},
                                                      {"+ aero_drag", kEffectAeroDrag}};
  for (const auto& [what, bit] : toggles) {
    RomVehicle e = v;
    e.effects ^= bit;
    e.drag_area = 3.0;
    report("18dof", what, [&] { return loop_seconds<Rom18>(e, in); });
  }
  return 0;
}
