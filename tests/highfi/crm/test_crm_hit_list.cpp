// The GPU soil loop sums its hits from a short list per thread (HitList, highfi/crm/sph_neighbours.hpp),
// flushed when any lane of the warp holds enough of them, or when the list is full. When the lists are
// flushed must not change what is summed, nor its order: a plate pushed into a bed with every effect
// that has pair sums of its own comes out with the same bits whether the lists are flushed after every
// row, at the default, or only when full (which takes the full list's own flush, at more than 32 hits
// a particle). The CPU has no list: its sums over the same neighbours are the CUDA half of
// test_crm_cpu_gpu.cpp's twin.
#include <catch2/catch.hpp>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "highfi/crm/crm_solver.hpp"
#include "tests/highfi/crm/crm_test_scenes.hpp"
#include "tests/skip.hpp"

using namespace terracal;

namespace {

nlohmann::json plate_scene() {
  nlohmann::json j = test::bed_scene_json(0.01, 14, 8);
  j["resolution"]["h_over_d0"] = 1.4;  // about 90 neighbours: every list fills more than twice
  j["effects"] = {"artificial_viscosity", "hourglass_damping", "hourglass_stiffness"};
  j["bodies"] = {{{"name", "plate"},
                  {"shape", {{"type", "disc"}, {"radius", 0.04}, {"thickness", 0.02}}},
                  {"position", {0.07, 0.07, 0.08 + 0.012}},
                  {"motion", {{"type", "prescribed"}, {"linear_velocity", {0, 0, -0.2}}}}}};
  return j;
}

HostSoil run_flushing_at(const char* flush_at) {
  if (flush_at)
    setenv("TERRACAL_CUDA_HIT_FLUSH", flush_at, 1);
  else
    unsetenv("TERRACAL_CUDA_HIT_FLUSH");
  CrmSolver s(test::scene_from(plate_scene()), CrmDevice::kCuda);
  unsetenv("TERRACAL_CUDA_HIT_FLUSH");
  for (int k = 0; k < 60; ++k) s.step();
  std::printf("hit lists flushed at %s: plate force %.9g N\n", flush_at ? flush_at : "the default",
              s.wrenches()[0].force.z);
  return s.soil();
}

long differing_particles(const HostSoil& a, const HostSoil& b) {
  const auto same = [](const Vec4<double>& p, const Vec4<double>& q) {
    return p.x == q.x && p.y == q.y && p.z == q.z && p.w == q.w;
  };
  long differ = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    differ += a.ids[i] != b.ids[i] || !same(a.pos[i], b.pos[i]) || !same(a.vel[i], b.vel[i]) ||
              !same(a.s0[i], b.s0[i]) || !same(a.s1[i], b.s1[i]);
  return differ;
}

}  // namespace

TEST_CASE("CRM on the GPU: when the hit lists are flushed does not change the bits", "[highfi][crm][gpu]") {
  if (!test::cuda_device_or_skip("CRM hit lists")) return;
  const HostSoil every_row = run_flushing_at("1");
  const HostSoil by_default = run_flushing_at(nullptr);
  const HostSoil when_full = run_flushing_at("33");
  REQUIRE(every_row.size() == by_default.size());
  REQUIRE(every_row.size() == when_full.size());
  REQUIRE(every_row.size() > 1000);
  CHECK(differing_particles(every_row, by_default) == 0);
  CHECK(differing_particles(every_row, when_full) == 0);
}
