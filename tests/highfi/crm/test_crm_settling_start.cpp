// Where settling starts (settle_jitter): a bed released from the exact lattice stays still, then
// rearranges in a burst (results/crm_settling); a jittered start sets that motion going at once.
// - the jitter moves each particle by at most the amplitude per axis, the same seed gives the same
//   bed, another seed (settle_seed) another, and both keys are validated and part of the settled
//   bed's cache key;
// - the motion a jittered start sets going dies out: the bed comes to rest without losing height.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/errors.hpp"
#include "highfi/crm/crm_checkpoint.hpp"
#include "highfi/crm/crm_solver.hpp"
#include "highfi/crm/crm_terrain.hpp"
#include "tests/highfi/crm/crm_test_scenes.hpp"

using namespace terracal;

TEST_CASE("CRM: the jittered start moves particles by at most the amplitude, reproducibly", "[highfi][crm]") {
  nlohmann::json j = test::bed_scene_json(0.05, 6, 5);
  j["settle_jitter"] = 0.1;
  const CrmScene sc = test::scene_from(j);
  const HostSoil lattice = initial_bed(sc), a = settling_start(sc), b = settling_start(sc);
  REQUIRE(a.size() == lattice.size());
  double largest = 0, mean_z = 0;
  bool same = true;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double dx = a.pos[i].x - lattice.pos[i].x, dy = a.pos[i].y - lattice.pos[i].y,
                 dz = a.pos[i].z - lattice.pos[i].z;
    largest = std::max({largest, std::abs(dx), std::abs(dy), std::abs(dz)});
    mean_z += dz / double(a.size());
    same = same && a.pos[i].x == b.pos[i].x && a.pos[i].z == b.pos[i].z;
    CHECK(a.s0[i].z == lattice.s0[i].z);  // the lithostatic stress goes with the particle
  }
  CHECK(same);
  CHECK(largest <= 0.1 * 0.05 + 1e-15);
  CHECK(largest > 0.08 * 0.05);  // 150 particles x 3 axes: one comes near the bound
  CHECK(std::abs(mean_z) < 0.01 * 0.05);
  // No jitter is the lattice itself; the amount is part of the settled bed's cache key.
  CrmScene exact = sc;
  exact.settle_jitter = 0;
  const HostSoil l2 = settling_start(exact);
  for (std::size_t i = 0; i < l2.size(); ++i) CHECK(l2.pos[i].z == lattice.pos[i].z);
  CHECK(crm_fingerprint(sc, CrmDevice::kCpu, false) != crm_fingerprint(exact, CrmDevice::kCpu, false));
  // Another seed is another bed, with its own cache key; the default seed leaves the key as it was.
  nlohmann::json j2 = j;
  j2["settle_seed"] = 7;
  const CrmScene other = test::scene_from(j2);
  const HostSoil c = settling_start(other);
  std::size_t moved = 0;
  for (std::size_t i = 0; i < c.size(); ++i) moved += c.pos[i].x != a.pos[i].x;
  CHECK(moved > c.size() / 2);
  CHECK(crm_fingerprint(sc, CrmDevice::kCpu, false) != crm_fingerprint(other, CrmDevice::kCpu, false));
  CHECK(crm_fingerprint(sc, CrmDevice::kCpu, false).find("settle seed") == std::string::npos);
  j2["settle_seed"] = -1;
  CHECK_THROWS_WITH(test::scene_from(j2), Catch::Contains("settle_seed"));
  j["settle_jitter"] = 0.5;
  try {
    test::scene_from(j);
    FAIL("settle_jitter 0.5 was accepted");
  } catch (const InputError& e) {
    CHECK_THAT(e.what(), Catch::Contains("settle_jitter") && Catch::Contains("0.5"));
  }
}

TEST_CASE("CRM: the motion a jittered start sets going dies out", "[highfi][crm]") {
  // 0.6 x 0.6 m, 0.96 m deep at 0.06 m (1,600 particles; about 5 s on one core).
  const double d0 = 0.06;
  nlohmann::json j = test::bed_scene_json(d0, 10, 16);
  j["settle_jitter"] = 0.1;
  const CrmScene sc = test::scene_from(j);
  const HostSoil start = settling_start(sc);
  CrmSolver solver(sc, test::validation_device(), &start);
  auto rms_speed = [&] {
    const SoilStats st = solver.stats();
    return std::sqrt(2 * st.kinetic_energy / st.mass);
  };
  double early = 0;
  while (solver.time() < 0.05) solver.step();
  early = rms_speed();
  while (solver.time() < 0.6) solver.step();
  const double late = rms_speed();
  REQUIRE(solver.stats().nonfinite == 0);
  INFO("rms speed " << early << " m/s at 0.05 s, " << late << " m/s at 0.6 s");
  CHECK(early > 0.005);       // the jitter sets the bed moving (a lattice bed: under 0.001 m/s)
  CHECK(late < 0.1 * early);  // and that motion dies out
  CHECK(late < 0.003);
  // It comes to rest at its height: the surface within a third of a spacing of the fill height.
  CHECK(std::abs(bed_surface_height(solver.soil(), sc) - 16 * d0) < d0 / 3);
}
