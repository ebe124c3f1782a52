// The measure behind the bin-size and run-length checks (a bigger bin or a longer run moves a rig's
// curve by < 5 %; docs/decisions.md):
// two runs sample their curves at different x when their time steps differ, so the check curve is
// read at the base curve's x, not by sample number.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/errors.hpp"
#include "virtual_bevameter/curve_change.hpp"

using namespace terracal;
using rigs::Curve;

namespace {
// y = scale * x^0.8 (a plate's loading leg) at n samples from dx to n * dx.
Curve power_curve(std::size_t n, double dx, double scale) {
  Curve c;
  for (std::size_t i = 1; i <= n; ++i) {
    c.x.push_back(double(i) * dx);
    c.y.push_back(scale * std::pow(double(i) * dx, 0.8));
  }
  return c;
}
}  // namespace

TEST_CASE("curve_change: the same curve sampled at other sinkages has not moved", "[rigs][checks]") {
  // The checked and the 1.5x plate bins of results/plate_bin_check wrote rows 1.118 and 1.104 mm
  // apart; compared sample by sample the same law would read as moved by about 1 %.
  const Curve base = power_curve(107, 1.1177e-3, 1e5), check = power_curve(108, 1.1040e-3, 1e5);
  CHECK(rigs::curve_change(base, base) == 0.0);
  CHECK(rigs::curve_change(base, check) < 1e-3);
}

TEST_CASE("curve_change: a curve 4 % higher moves by 4 % of the larger", "[rigs][checks]") {
  const Curve base = power_curve(100, 1e-3, 1e5), check = power_curve(130, 0.77e-3, 1.04e5);
  CHECK(rigs::curve_change(base, check) == Approx(0.04 / 1.04).epsilon(2e-3));
  CHECK(rigs::curve_change(check, base) == Approx(0.04 / 1.04).epsilon(2e-3));
}

TEST_CASE("curve_change: only the x both curves cover is compared", "[rigs][checks]") {
  // The check stops at half the base's range; beyond it the base is 10x larger, which must not count.
  Curve base = power_curve(100, 1e-3, 1e5);
  for (std::size_t i = 50; i < base.y.size(); ++i) base.y[i] *= 10;
  const Curve check = power_curve(49, 1e-3, 1e5);
  CHECK(rigs::curve_change(base, check) < 1e-12);
  CHECK(rigs::curve_change(base, power_curve(3, 1e-3, 1e5)) == 0.0);  // under five common samples
}

TEST_CASE("curve_change: a curve whose x falls back, or sizes that differ, is refused", "[rigs][checks]") {
  Curve bad = power_curve(10, 1e-3, 1);
  std::swap(bad.x[3], bad.x[4]);
  CHECK_THROWS_AS(rigs::curve_change(bad, power_curve(10, 1e-3, 1)), InputError);
  Curve uneven = power_curve(10, 1e-3, 1);
  uneven.y.pop_back();
  CHECK_THROWS_AS(rigs::curve_change(power_curve(10, 1e-3, 1), uneven), InputError);
}

TEST_CASE("mean_curve: realisations sampled at other x average to the law they scatter about", "[rigs][checks]") {
  // Three runs of one law, 6 % above, on it, and 6 % below, each sampled at its own x: the mean is
  // the law, read at the first's x over the range all three cover.
  const Curve up = power_curve(100, 1e-3, 1.06e5), mid = power_curve(120, 0.85e-3, 1e5),
              down = power_curve(90, 1.05e-3, 0.94e5);
  const Curve mean = rigs::mean_curve({up, mid, down});
  // up's x run from 1 to 100 mm; mid covers 0.85-102 mm and down 1.05-94.5 mm: 2 ... 94 mm lie in all three.
  CHECK(mean.x.size() == 93);
  CHECK(mean.x.front() == up.x[1]);
  // Within the error of reading x^0.8 linearly between samples a millimetre apart.
  for (std::size_t i = 0; i < mean.x.size(); ++i)
    CHECK(mean.y[i] == Approx(1e5 * std::pow(mean.x[i], 0.8)).epsilon(3e-3));
  CHECK(rigs::curve_change(mean, mid) < 1e-3);
  // The scatter is the largest pair: up against down, 12 % of the larger.
  CHECK(rigs::realisation_scatter({up, mid, down}) == Approx(0.12 / 1.06).epsilon(3e-3));
  CHECK(rigs::realisation_scatter({mid}) == 0.0);
  CHECK_THROWS_AS(rigs::mean_curve({}), InputError);
}
