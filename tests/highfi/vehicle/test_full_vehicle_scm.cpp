// The full HMMWV on SCM dry sand: at rest each wheel sinks as the single-wheel rig's wheel of the same
// shape sinks under the same load; at constant throttle it drives off, and its speed and wheel slips
// settle and stay finite.
#include <catch2/catch.hpp>

#include <cmath>

#include "highfi/vehicle/vehicle_run.hpp"
#include "tests/lowfi/scm_test_soils.hpp"
#include "virtual_bevameter/wheel_rig.hpp"

using namespace terracal;
using namespace terracal::vehicle;

namespace {
VehicleRunOptions on_dry_sand(double end_time, double grid) {
  VehicleRunOptions o;
  o.end_time = end_time;
  o.output_rate = 20;
  o.rtol = 1e-3;  // the terrain command's default on SCM (docs/decisions.md)
  o.soil = test::scm_dry_sand();
  o.scm.grid = grid;
  o.scm.time_step = 1e-3;
  o.scm.effects.enable<lowfi::ScmDamping>();
  return o;
}
}  // namespace

TEST_CASE("full vehicle on SCM: each wheel's static sinkage is the single-wheel rig's under its load",
          "[vehicle][scm]") {
  const FullVehicleSpec spec = load_full_vehicle("hmmwv");
  const DriverSeries idle = DriverSeries::from_rows({0, 1}, {0, 0}, {0, 0}, {0, 0});
  // At a 0.01 m grid: at 0.02 m the 0.254 m wide wheel spans 12.7 nodes and its sinkage depends on
  // where it sits on the grid (the vehicle's wheels 7-13 % deeper than the rig's centred one).
  const VehicleRunOptions o = on_dry_sand(1.0, 0.01);
  const VehicleRunResult r = run_full_vehicle(spec, &idle, nullptr, o);
  REQUIRE(r.wheels.size() >= 4);
  double load = 0;
  for (std::size_t k = r.wheels.size() - 4; k < r.wheels.size(); ++k) {
    const WheelSample& w = r.wheels[k];
    load += w.contact.fz;
    rigs::WheelSpec wheel;
    wheel.radius = spec.scm_wheel.radius;
    wheel.width = spec.scm_wheel.width;
    wheel.mass = w.contact.fz / 9.81;
    wheel.angular_velocity = 0;
    // The rig's wheel loaded as the vehicle is set down: linearly over half the settling time.
    rigs::WheelRun run;
    run.duration = 3.0;
    run.load_ramp = 0.5 * o.settle_time;
    const double rig = rigs::run_wheel(lowfi::ScmSite(*o.soil, o.scm), wheel, 0.0, run).sinkage;
    INFO("wheel " << w.wheel << ": load " << w.contact.fz << " N, sinkage " << w.contact.sinkage << " m, rig " << rig
                  << " m");
    CHECK(std::isfinite(w.contact.sinkage));
    CHECK(w.contact.sinkage > 0.02);  // a real sinkage into sand
    CHECK(std::abs(w.contact.sinkage - rig) < 0.05 * rig);
  }
  // The four wheels carry the vehicle (vertical forces only at rest, up to the held soil's lag).
  CHECK(std::abs(load - spec.total_mass() * 9.81) < 0.01 * spec.total_mass() * 9.81);
  CHECK(r.max_constraint_violation < 1e-6);
}

TEST_CASE("full vehicle on SCM: at constant throttle its speed and wheel slips settle", "[vehicle][scm]") {
  const FullVehicleSpec spec = load_full_vehicle("hmmwv");
  const DriverSeries throttle = DriverSeries::from_rows({0, 8}, {0, 0}, {0.5, 0.5}, {0, 0});
  const VehicleRunResult r = run_full_vehicle(spec, &throttle, nullptr, on_dry_sand(8.0, 0.02));
  bool finite = true;
  for (const VehicleSample& s : r.samples) finite = finite && std::isfinite(s.x) && std::isfinite(s.vx);
  for (const WheelSample& w : r.wheels) finite = finite && std::isfinite(w.contact.sx) && std::isfinite(w.contact.fz);
  REQUIRE(finite);
  // The last 2 s: the speed changes little, every wheel's slip stays within a narrow band.
  double v_lo = 1e9, v_hi = -1e9, s_lo = 1e9, s_hi = -1e9;
  for (const VehicleSample& s : r.samples)
    if (s.time >= 6) v_lo = std::min(v_lo, s.vx), v_hi = std::max(v_hi, s.vx);
  for (const WheelSample& w : r.wheels)
    if (w.time >= 6) s_lo = std::min(s_lo, w.contact.sx), s_hi = std::max(s_hi, w.contact.sx);
  INFO("speed between " << v_lo << " and " << v_hi << " m/s, slips between " << s_lo << " and " << s_hi);
  CHECK(v_lo > 1.0);                                                // it drives off
  CHECK(v_hi - v_lo < 0.05 * v_hi);                                 // and its speed settles
  CHECK(s_lo > 0.0);                                                // every wheel drives
  CHECK(s_hi < 0.5);                                                // none digs in
  CHECK(s_hi - s_lo < 0.1);                                         // the slips settle
  CHECK(std::abs(r.samples.back().y) < 0.01 * r.samples.back().x);  // straight
  CHECK(r.max_constraint_violation < 1e-5);                         // at rtol 1e-3
}
