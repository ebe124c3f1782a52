#include "apps/wheel_table.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/errors.hpp"

namespace terracal::app {

namespace {

void check_increasing(const std::vector<double>& x, const char* option) {
  if (x.empty()) throw InputError(fmt::format("{}: give at least one value", option));
  for (std::size_t i = 1; i < x.size(); ++i)
    if (!(x[i] > x[i - 1]))
      throw InputError(fmt::format("{}: values must increase; {} follows {}", option, x[i], x[i - 1]));
}

// The run of the largest slip angle: the site is sized for its travel across.
rigs::WheelRun widest(const WheelTablePlan& plan) {
  rigs::WheelRun r = plan.run;
  r.slip_angle = plan.angles.back();
  return r;
}

}  // namespace

void check_wheel_table(const SoilChoice& soil, const TerrainOptions& o, const rigs::WheelSpec& wheel,
                       const WheelTablePlan& plan) {
  if (soil.solver != SoilModel::kScm) throw InputError("wheel-table: the rig runs on SCM (--scm SCM.json)");
  check_increasing(plan.loads, "--loads");
  check_increasing(plan.slips, "--slips");
  check_increasing(plan.angles, "--slip-angles");
  for (double l : plan.loads) check_range(Range{0, 1e7, true, false, "N"}, l, "--loads");
  if (plan.slips.back() <= 0)
    throw InputError(fmt::format("--slips: needs a slip above zero (largest {})", plan.slips.back()));
  if (std::find(plan.slips.begin(), plan.slips.end(), 0.0) == plan.slips.end())
    throw InputError("--slips: needs 0 (the thrust and resistance of a wheel rolling without slip)");
  if (plan.angles.size() > 1 && plan.angles.front() != 0)
    throw InputError(fmt::format("--slip-angles: with several angles the first must be 0 (got {})", plan.angles[0]));
  for (double a : plan.angles) check_range(rigs::WheelRanges::kSlipAngle, a, "--slip-angles");
  rigs::WheelSpec heaviest = wheel;
  heaviest.mass = plan.loads.back() / norm(soil.gravity);
  check_wheel_sweep(SoilModel::kScm, soil, o, heaviest, plan.slips, widest(plan));
}

rom::TerrainTable run_wheel_table(const SoilChoice& soil, const TerrainOptions& o, const rigs::WheelSpec& wheel,
                                  const WheelTablePlan& plan) {
  check_wheel_table(soil, o, wheel, plan);
  rom::TerrainTable t;
  t.load = plan.loads;
  t.slip = plan.slips;
  t.angle = plan.angles;
  t.radius = wheel.radius;
  t.width = wheel.width;
  t.duration = plan.run.duration;
  const std::size_t n = t.load.size() * t.slip.size() * t.angle.size();
  for (auto* a : {&t.dbp, &t.torque, &t.sinkage, &t.lateral}) a->assign(n, 0.0);
  const auto site = wheel_site(soil, o, wheel, plan.slips, widest(plan));
  const double g = norm(soil.gravity);
  std::atomic<long> done{0};
  std::mutex failure_mutex;
  std::exception_ptr failure;
  // Each run has its own soil: the runs are independent, and longer at high slip, so they are
  // handed out one at a time.
#pragma omp parallel for schedule(dynamic, 1)
  for (long k = 0; k < long(n); ++k) {
    try {
      const std::size_t a = std::size_t(k) % t.angle.size(), s = (std::size_t(k) / t.angle.size()) % t.slip.size(),
                        l = std::size_t(k) / (t.angle.size() * t.slip.size());
      rigs::WheelSpec w = wheel;
      w.mass = t.load[l] / g;
      rigs::WheelRun run = plan.run;
      run.slip_angle = t.angle[a];
      const rigs::WheelResult r = rigs::run_wheel(*site, w, t.slip[s], run);
      const std::size_t i = t.index(l, s, a);
      t.dbp[i] = r.dbp;
      t.torque[i] = r.torque;
      t.sinkage[i] = r.sinkage;
      t.lateral[i] = r.lateral;
      if (const std::string why = rigs::unsteady_reason(r); !why.empty())
        spdlog::warn("wheel-table: load {} N, slip angle {} rad: {}", t.load[l], t.angle[a], why);
      spdlog::info("wheel-table: {} of {} runs done (load {} N, slip {}, slip angle {} rad: DBP {:.4g} N, torque "
                   "{:.4g} N m, sinkage {:.4g} m, lateral {:.4g} N; {:.3g} s wall)",
                   ++done, n, t.load[l], t.slip[s], t.angle[a], r.dbp, r.torque, r.sinkage, r.lateral,
                   r.wall_seconds);
    } catch (...) {
      std::lock_guard<std::mutex> lock(failure_mutex);
      if (!failure) failure = std::current_exception();
    }
  }
  if (failure) std::rethrow_exception(failure);
  rom::finish_coefficients(t);
  return t;
}

}  // namespace terracal::app
