// The SCM wheel's posterior band of the pipeline report (apps/wheel_band.hpp): posterior sets through
// the steady SCM wheel, and its check against the time-stepping SCM wheel.
#include <catch2/catch.hpp>

#include <cmath>

#include "apps/wheel_band.hpp"
#include "lowfi/scm_steady_wheel.hpp"

using namespace terracal;
using namespace terracal::app;

TEST_CASE("the SCM wheel band brackets its sets and agrees with the time-stepping wheel", "[apps][wheel][band]") {
  // Three sets of dry sand that differ in Kphi by +-10 %: the band at each slip lies between the
  // lightest and the stiffest set's steady values, and the stiffer soil sinks less.
  lowfi::ScmSoil base = lowfi::reference_dry_sand();
  std::vector<lowfi::ScmSoil> sets;
  for (double f : {0.9, 1.0, 1.1}) {
    lowfi::ScmSoil s = base;
    s.Kphi *= f;
    sets.push_back(s);
  }
  rigs::WheelSpec wheel;  // 0.47 m, 0.25 m, 108 kg, 1 rad/s
  TerrainOptions scm;
  scm.grid = 0.01;
  scm.step = 0;
  rigs::WheelRun run;
  run.duration = 3;
  const std::vector<double> slips{0.1, 0.3, 0.5};
  const Vec3<double> g{0, 0, -9.81};
  const WheelBand b = scm_wheel_band(sets, wheel, g, slips, false, scm, run, 2);
  REQUIRE(b.sets == 3);
  CHECK(b.failed == 0);
  for (std::size_t i = 0; i < slips.size(); ++i) {
    const auto soft = lowfi::scm_steady_wheel(sets[0], {wheel.radius, wheel.width}, wheel.mass * 9.81, slips[i]);
    const auto stiff = lowfi::scm_steady_wheel(sets[2], {wheel.radius, wheel.width}, wheel.mass * 9.81, slips[i]);
    INFO("slip " << slips[i]);
    CHECK(b.q95[2][i] <= soft.sinkage * (1 + 1e-6));
    CHECK(b.q05[2][i] >= stiff.sinkage * (1 - 1e-6));
    CHECK(b.q05[2][i] < b.q50[2][i]);
    CHECK(b.q50[2][i] < b.q95[2][i]);
  }
  // The check: the steady model within 3 % of the time-stepping wheel (of each quantity) at the
  // sweep's middle slip, as tests/lowfi/test_scm_steady_wheel.cpp holds it over the whole sweep.
  REQUIRE(b.check_steady.size() == 2);
  CHECK(b.check_slip == 0.3);
  for (std::size_t k = 0; k < b.check_steady.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      INFO("set " << k << ", quantity " << c << ": steady " << b.check_steady[k][c] << ", time-stepping "
                  << b.check_stepped[k][c]);
      CHECK(std::abs(b.check_steady[k][c] - b.check_stepped[k][c]) <= 0.03 * std::abs(b.check_stepped[k][c]));
    }
}
