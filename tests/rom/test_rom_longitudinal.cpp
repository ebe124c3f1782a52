// Straight-line behaviour: full throttle from rest (monotonic speed, shifts at the configured engine
// speeds, no drift), coast-down against the resistance model, braking to rest.
#include <cmath>

#include <catch2/catch.hpp>

#include "rom/rom18.hpp"
#include "tests/rom/rom_test_vehicles.hpp"

using namespace terracal;
using namespace terracal::rom;
using namespace terracal::rom::testing;

TEST_CASE("rom: full throttle from rest: speed rises, shifts at the upshift speed, no lateral drift", "[rom]") {
  const RomVehicle v = hmmwv();
  for (RomModel m : {RomModel::k11Dof, RomModel::k18Dof, RomModel::k24Dof}) {
    const RomRunResult r = run(v, constant_inputs(0, 1, 0), options(m, 15.0, 0.0));
    int shifts = 0;
    for (std::size_t i = 1; i < r.samples.size(); ++i) {
      const RomSample &a = r.samples[i - 1], &b = r.samples[i];
      INFO(model_name(m) << " t = " << b.time);
      CHECK(b.vx >= a.vx - 1e-9);
      CHECK(std::fabs(b.y) < 1e-6);
      if (b.gear > a.gear) {
        ++shifts;
        const double up_rpm = v.powertrain.upshift_speed[a.gear - 1] * 30 / M_PI;
        CHECK(std::max(a.engine_speed_rpm, b.engine_speed_rpm) >= up_rpm);
      }
    }
    CHECK(shifts == v.powertrain.gears - 1);
    CHECK(r.samples.back().vx > 15.0);
  }
}

TEST_CASE("rom: coast-down follows rolling resistance and aerodynamic drag", "[rom]") {
  RomVehicle v = frictionless_hmmwv();
  v.effects |= kEffectRollingResistance | kEffectAeroDrag;
  v.drag_area = 2.5;
  const RomRunResult r = run(v, constant_inputs(0, 0, 0), options(RomModel::k18Dof, 2.0, 25.0));
  const RomSample& s = r.samples[100];  // t = 1 s: the transients from the initial state are gone
  const double r0 = v.tire[0].unloaded_radius;
  const double m_eff = v.total_mass() + 4 * v.tire[0].wheel_inertia / (r0 * r0);
  const double resist =
      0.5 * v.air_density * v.drag_area * s.vx * s.vx + v.tire[0].rolling_resistance * v.total_mass() * v.gravity;
  INFO("deceleration " << -s.ax << " m/s^2 at " << s.vx << " m/s; model " << resist / m_eff);
  CHECK(-s.ax == Approx(resist / m_eff).epsilon(0.03));
}

TEST_CASE("rom: full braking from 30 m/s ends at rest and stays there", "[rom][hard]") {
  const RomVehicle v = hmmwv();
  for (RomIntegrator integ : {RomIntegrator::kHalfImplicit, RomIntegrator::kCvodes}) {
    RomRunOptions o = options(RomModel::k18Dof, 12.0, 30.0);
    o.integrator = integ;
    const RomRunResult r = run(v, constant_inputs(0, 0, 1), o);
    double stop_time = -1;
    for (const RomSample& s : r.samples) {
      REQUIRE(std::isfinite(s.vx));
      if (stop_time < 0 && std::fabs(s.vx) < 1e-3) stop_time = s.time;
      // The body rocks on the tires' tread springs (about 2.8 Hz, 18 % damped for the HMMWV) once the
      // wheels stop; within 2 s it is still.
      INFO(integrator_name(integ) << " t = " << s.time << " vx " << s.vx);
      if (stop_time >= 0) CHECK(std::fabs(s.vx) < 0.25);
      if (stop_time >= 0 && s.time > stop_time + 2.0) CHECK(std::fabs(s.vx) < 1e-3);
    }
    INFO(integrator_name(integ) << ": stopped at " << stop_time << " s");
    CHECK(stop_time > 2.0);
    CHECK(stop_time < 8.0);
  }
}
