// The integrators against each other: the half-implicit scheme converges to a tight CVODES solution
// at its order (first) as the step shrinks.
#include <cmath>

#include <catch2/catch.hpp>

#include "tests/rom/rom_test_vehicles.hpp"

using namespace terracal;
using namespace terracal::rom;
using namespace terracal::rom::testing;

namespace {
// Largest deviation of position (m) over the run, sampled at 100 Hz.
double path_error(const RomRunResult& a, const RomRunResult& b) {
  double e = 0;
  for (std::size_t i = 0; i < std::min(a.samples.size(), b.samples.size()); ++i)
    e = std::max(e, std::hypot(a.samples[i].x - b.samples[i].x, a.samples[i].y - b.samples[i].y));
  return e;
}
}  // namespace

TEST_CASE("rom: the half-implicit scheme converges to CVODES at first order", "[rom]") {
  RomVehicle v = hmmwv();
  // One gear and no dry friction: the two integrators then solve the same smooth ODE (shift times
  // and the implicit stop of a braked wheel are where they differ by design).
  v.powertrain.gears = 1;
  v.powertrain.gear_ratio[0] = 0.08;
  v.effects &= ~kEffectRollingResistance;
  const DriverSeries inputs =
      DriverSeries::from_rows({0, 1, 2, 3, 4}, {0, 0.3, -0.3, 0.1, 0}, {0.2, 0.6, 0.4, 0.5, 0.3}, {0, 0, 0, 0, 0});
  for (RomModel m : {RomModel::k11Dof, RomModel::k18Dof, RomModel::k24Dof}) {
    RomRunOptions o = options(m, 4.0, 10.0);
    o.integrator = RomIntegrator::kCvodes;
    o.rtol = 1e-10;
    o.atol = 1e-12;
    const RomRunResult reference = run(v, inputs, o);
    o.integrator = RomIntegrator::kHalfImplicit;
    double previous = 0;
    for (double h : {2e-3, 1e-3, 5e-4}) {
      o.step = h;
      const double e = path_error(run(v, inputs, o), reference);
      INFO(model_name(m) << ": step " << h << " error " << e << " m, previous " << previous);
      if (previous > 0) CHECK(previous / e == Approx(2.0).margin(0.4));
      previous = e;
    }
    CHECK(previous < 0.05);
  }
}
