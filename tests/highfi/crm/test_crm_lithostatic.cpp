// Validation 8: a settled bed carries its own weight, sigma_zz(depth) = -rho g depth, with a
// lateral stress ratio in [0.3, 1.0].
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <map>

#include "highfi/crm/crm_solver.hpp"
#include "tests/highfi/crm/crm_test_scenes.hpp"

using namespace terracal;

TEST_CASE("CRM: a settled bed is lithostatic", "[highfi][crm]") {
  const double d0 = 0.01;
  const int layers = 12;
  CrmScene sc = test::scene_from(test::bed_scene_json(d0, 12, layers));
  // Starts from the lithostatic estimate (as settling does) with the bed released at t = 0: the
  // boundary markers, the stress divergence and the free surface must hold it for 0.15 s.
  CrmSolver solver(sc, test::validation_device());
  const long n = long(std::ceil(0.15 / solver.time_step()));
  for (long s = 0; s < n; ++s) solver.step();
  const SoilStats st = solver.stats();
  REQUIRE(st.nonfinite == 0);
  const HostSoil soil = solver.soil();
  // Layer averages of the stress and the top of the bed.
  std::map<int, std::array<double, 4>> layer;  // sum szz, sxx+syy / 2, z, count
  double top = 0;
  for (std::size_t i = 0; i < soil.size(); ++i) top = std::max(top, soil.pos[i].z);
  for (std::size_t i = 0; i < soil.size(); ++i) {
    const int k = int(std::floor(soil.pos[i].z / d0));
    auto& a = layer[k];
    a[0] += soil.s0[i].z;
    a[1] += 0.5 * (soil.s0[i].x + soil.s0[i].y);
    a[2] += soil.pos[i].z;
    a[3] += 1;
  }
  const double rho_g = sc.soil.density * 9.81;
  int checked = 0;
  for (const auto& [k, a] : layer) {
    const double z = a[2] / a[3], szz = a[0] / a[3], sxx = a[1] / a[3];
    const double depth = top + 0.5 * d0 - z;  // the free surface lies half a spacing above the top particles
    const double expected = -rho_g * depth;
    std::printf("layer %2d z=%.4f depth=%.4f szz=%9.1f expected=%9.1f ratio=%.3f K=%.3f\n", k, z, depth, szz, expected,
                szz / expected, sxx / szz);
    if (depth < 2.5 * d0) continue;  // below the top two particle layers
    CHECK(szz == Approx(expected).epsilon(0.05));
    CHECK(sxx / szz >= 0.3);
    CHECK(sxx / szz <= 1.0);
    ++checked;
  }
  CHECK(checked >= layers - 3);
  // At rest: the kinetic energy per unit weight is tiny.
  CHECK(st.max_speed < 0.01);
}
