// active_domain freezes the soil away from moving bodies. A wheel driven through a bed: its forces
// with the active domain (default margin) match the full domain's within 1 %, while part of the bed
// stays frozen; with a margin of 0.04 m they fall 17 % short, so the test can tell. Runs on the
// CPU, and on the GPU with TERRACAL_TEST_DEVICE=cuda (crm_test_scenes.hpp).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <tuple>
#include <utility>

#include "highfi/crm/crm_solver.hpp"
#include "tests/highfi/crm/crm_test_scenes.hpp"
#include "tests/highfi/crm/soil_compare.hpp"
#include "tests/skip.hpp"

using namespace terracal;

namespace {

// A bin 0.5 m long, 8 spacings deep, with a wheel sunk 1 cm driven along it at slip 0.3.
nlohmann::json wheel_scene(bool active) {
  const double d0 = 0.01, radius = 0.05, speed = 0.2, slip = 0.3;
  nlohmann::json j = test::bed_scene_json(d0, 16, 8);
  j["bin"]["size"] = {0.5, 0.16, 0.12};
  j["bodies"] = {{{"name", "wheel"},
                  {"shape", {{"type", "cylinder"}, {"radius", radius}, {"width", 0.04}}},
                  {"position", {0.12, 0.08, 0.08 + radius - 0.01}},
                  {"motion",
                   {{"type", "prescribed"},
                    {"linear_velocity", {speed, 0, 0}},
                    {"angular_velocity", {0, speed / (radius * (1 - slip)), 0}}}}}};
  if (active) j["effects"].push_back("active_domain");  // the default margin, 0.1 m
  return j;
}

struct WheelRun {
  Vec3<double> force;  // mean over the second half
  long frozen;         // frozen particles at the end
};

WheelRun drive(bool active, double duration) {
  CrmSolver s(test::scene_from(wheel_scene(active)), test::validation_device());
  const long n = long(duration / s.time_step());
  Vec3<double> sum{};
  for (long k = 0; k < n; ++k) {
    s.step();
    if (2 * k >= n) sum += s.wrenches()[0].force;
  }
  const SoilStats st = s.stats();
  CHECK(st.nonfinite == 0);
  return {(1.0 / double(n - n / 2)) * sum, st.frozen};
}

}  // namespace

TEST_CASE("CRM: active_domain keeps a driven wheel's forces within 1 % of the full domain's", "[highfi][crm]") {
  const double duration = 0.06;
  const WheelRun full = drive(false, duration), focused = drive(true, duration);
  std::printf("wheel: full domain F = (%.4f, %.4f, %.4f) N; active domain F = (%.4f, %.4f, %.4f) N, %ld frozen\n",
              full.force.x, full.force.y, full.force.z, focused.force.x, focused.force.y, focused.force.z,
              focused.frozen);
  CHECK(full.frozen == 0);
  CHECK(focused.frozen > 0);
  CHECK(full.force.z > 0);  // the bed carries the sunk wheel
  CHECK(focused.force.z == Approx(full.force.z).epsilon(0.01));
  CHECK(std::abs(focused.force.x - full.force.x) <= 0.01 * std::abs(full.force.z));
}

// An active domain whose box covers the whole bed freezes nothing, so it must give the full domain's
// state. On the GPU this runs the stages over the compacted lists, a group of lanes per particle and
// per marker (core/lane_group.hpp): the sums come out in another order, so the two agree to float
// round-off there and bit for bit on the CPU.
TEST_CASE("CRM: an active domain that covers the whole bed reproduces the full domain", "[highfi][crm]") {
  const auto run = [](bool active) {
    nlohmann::json j = wheel_scene(active);
    if (active) j["active_domain"] = {{"margin", 1.0}};
    CrmSolver s(test::scene_from(j), test::validation_device());
    const long n = long(0.02 / s.time_step());
    for (long k = 0; k < n; ++k) s.step();
    CHECK(s.stats().frozen == 0);
    return std::make_pair(s.soil(), s.wrenches()[0].force);
  };
  const auto [full, full_force] = run(false);
  const auto [focused, focused_force] = run(true);
  const double worst = test::largest_position_difference(full, focused);
  std::printf("whole-bed active domain: largest position difference %.3g m; wheel Fz %.6f against %.6f N\n", worst,
              focused_force.z, full_force.z);
  CHECK(worst <= 1e-6);  // 1e-4 spacings: round-off, not a missed neighbour or a lost sum
  CHECK(focused_force.z == Approx(full_force.z).epsilon(1e-4));
  CHECK(std::abs(focused_force.x - full_force.x) <= 1e-4 * std::abs(full_force.z));
}

// The markers' sort from two runs on the GPU (sph_sort.hpp: the fixed markers sorted once and merged
// with the wheel's at every pose) must give the order that sorting every marker gives, and so the same
// bits. The CPU sorts every marker; the merge's CPU twin is tests/highfi/crm/test_crm_sort_runs.cpp.
TEST_CASE("CRM: sorting the markers from two runs gives the bits of sorting them all", "[highfi][crm]") {
  if (test::validation_device() != CrmDevice::kCuda) {
    test::report_skip("CRM markers from two runs", "the CPU sorts every marker (TERRACAL_TEST_DEVICE=cuda runs it)");
    return;
  }
  const auto run = [](bool sort_all) {
    if (sort_all)
      setenv("TERRACAL_CRM_SORT_ALL", "1", 1);
    else
      unsetenv("TERRACAL_CRM_SORT_ALL");
    nlohmann::json j = wheel_scene(true);
    j["resolution"]["sort_skin"] = 0;  // the markers sorted at every pose: what the merge is compared on
    CrmSolver s(test::scene_from(j), test::validation_device());
    unsetenv("TERRACAL_CRM_SORT_ALL");
    for (int k = 0; k < 40; ++k) s.step();
    const SortCounts counts = s.engine().sort_counts();
    std::printf("marker sorts (sort_all %d): %ld of every marker, %ld merged\n", int(sort_all), counts.markers_full,
                counts.markers_merged);
    return std::make_tuple(s.soil(), s.wrenches()[0], counts);
  };
  const auto [all, all_wrench, all_counts] = run(true);
  const auto [runs, runs_wrench, runs_counts] = run(false);
  CHECK(all_counts.markers_merged == 0);
  CHECK(runs_counts.markers_merged >= 80);  // both stages of every step
  REQUIRE(all.size() == runs.size());
  long differ = 0;
  for (std::size_t i = 0; i < all.size(); ++i) {
    const auto same = [](const Vec4<double>& a, const Vec4<double>& b) {
      return a.x == b.x && a.y == b.y && a.z == b.z && a.w == b.w;
    };
    differ += all.ids[i] != runs.ids[i] || !same(all.pos[i], runs.pos[i]) || !same(all.vel[i], runs.vel[i]) ||
              !same(all.s0[i], runs.s0[i]) || !same(all.s1[i], runs.s1[i]);
  }
  CHECK(differ == 0);
  // The GPU adds the wrench's block sums with atomics, in whatever order the blocks finish: its last
  // bits vary from run to run (the soil does not feel it: the wheel's motion is prescribed).
  const double tol = 1e-12 * (std::abs(all_wrench.force.z) + 1.0);
  CHECK(std::abs(all_wrench.force.x - runs_wrench.force.x) <= tol);
  CHECK(std::abs(all_wrench.force.z - runs_wrench.force.z) <= tol);
  CHECK(std::abs(all_wrench.torque.y - runs_wrench.torque.y) <= tol);
  CHECK(std::abs(all_wrench.force.z) > 1.0);  // the wheel bears on the soil
}
