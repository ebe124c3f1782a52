// Strongly compressed soil and the run's health checks: soil squeezed in a closed box keeps its
// mass (its density follows the volume, its pressure the density), and a run that goes bad is
// named as such, with the time, the place and what to try.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "core/errors.hpp"
#include "highfi/crm/crm_run.hpp"
#include "highfi/crm/crm_run_check.hpp"
#include "highfi/crm/crm_solver.hpp"
#include "tests/highfi/crm/crm_test_scenes.hpp"

using namespace terracal;

namespace {

constexpr double kD0 = 0.01;
constexpr int kCells = 6;  // the box is 6 x 6 spacings, filled 6 deep

// A lid as wide as the box, resting on the soil, driven down at 0.1 m/s for `duration` seconds.
nlohmann::json closed_box(double duration) {
  nlohmann::json j = test::bed_scene_json(kD0, kCells, kCells, 0.0);
  j["resolution"]["h_over_d0"] = 1.4;
  const double size = kCells * kD0, lid = 0.02;
  j["bodies"] = {{{"name", "lid"},
                  {"shape", {{"type", "box"}, {"size", {size, size, lid}}}},
                  {"position", {0.5 * size, 0.5 * size, size + 0.5 * lid}},
                  {"motion", {{"type", "prescribed"}, {"linear_velocity", {0, 0, -0.1}}}}}};
  j["bin"]["size"] = {size, size, 2 * size};
  j["duration"] = duration;
  return j;
}

}  // namespace

TEST_CASE("CRM: soil squeezed to 83 % of its volume in a closed box keeps its mass", "[highfi][crm][hard]") {
  // The lid goes down 0.01 m of the 0.06 m. Mass is conserved: sum m / rho = the box's volume under
  // the lid; and the pressure follows the density, p = K ln(rho / rho0) (the bed starts at rest
  // without stress), the tie the density's cap keeps (soil_stage.hpp). Squeezed further (to 78 %),
  // soil leaks out at the box's bottom edges: the walls' markers keep their spacing while the soil's
  // shrinks (results/crm_squeeze).
  const CrmScene sc = test::scene_from(closed_box(0.1));
  HostSoil bed = initial_bed(sc);
  for (auto& s : bed.s0) s = {0, 0, 0, 0};
  CrmSolver solver(sc, test::validation_device(), &bed);
  const CrmRunCheck health(solver);
  while (solver.time() < sc.duration - 0.5 * solver.time_step()) {
    solver.step();
    if (solver.steps() % kCrmCheckEvery == 0) {
      const auto bad = health.check(solver);
      INFO((bad ? bad->message : std::string()));
      REQUIRE(!bad);
    }
  }
  const HostSoil s = solver.soil();
  const double size = kCells * kD0, m = sc.soil.density * kD0 * kD0 * kD0, K = sc.soil.bulk_modulus();
  const double lid_bottom = solver.bodies()[0].position.z - 0.01;
  double volume = 0, p_sum = 0, tie_sum = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    volume += m / s.pos[i].w;
    p_sum += -(s.s0[i].x + s.s0[i].y + s.s0[i].z) / 3;
    tie_sum += K * std::log(s.pos[i].w / sc.soil.density);
  }
  const double box = size * size * lid_bottom, n = double(s.size());
  std::printf(
      "closed box: lid at %.4f m, soil volume %.4g m^3 against %.4g m^3 under the lid; mean p %.4g Pa, "
      "K ln(rho/rho0) %.4g Pa\n",
      lid_bottom, volume, box, p_sum / n, tie_sum / n);
  CHECK(solver.stats().lost == 0);
  CHECK(volume == Approx(box).epsilon(0.05));
  CHECK(p_sum / n == Approx(tie_sum / n).epsilon(0.1));
  // The mean pressure is that of the soil's own compression (to 5 %).
  CHECK(p_sum / n == Approx(K * std::log(size * size * size / volume)).epsilon(0.05));
  CHECK(lid_bottom == Approx(0.05).margin(1e-5));
}

TEST_CASE("CRM run check: a sound state passes, a bad one is named with its place", "[highfi][crm]") {
  nlohmann::json j = test::bed_scene_json(kD0, kCells, 4, 0.0);
  const CrmScene sc = test::scene_from(j);
  CrmSolver solver(sc, CrmDevice::kCpu);
  for (int k = 0; k < 20; ++k) solver.step();
  const CrmRunCheck health(solver);
  CHECK(!health.check(solver));
  const HostSoil good = solver.soil();
  auto with = [&](auto&& change) {
    HostSoil s = good;
    change(s);
    solver.restore(s, solver.bodies(), solver.time(), solver.steps());
    auto bad = health.check(solver);
    solver.restore(good, solver.bodies(), solver.time(), solver.steps());
    return bad;
  };
  SECTION("a non-finite particle") {
    const auto bad = with([](HostSoil& s) { s.vel[3].x = std::nan(""); });
    REQUIRE(bad);
    CHECK(bad->kind == "non-finite");
  }
  SECTION("a particle faster than the sound speed") {
    // Particle 86 is at [0.025, 0.025, 0.025] m, inside the bed.
    const auto bad = with([](HostSoil& s) { s.vel[86] = {0, 0, 40.0, s.vel[86].w}; });
    REQUIRE(bad);
    CHECK(bad->kind == "too fast");
    CHECK(bad->message.find("40") != std::string::npos);
    CHECK(bad->message.find("in the soil") != std::string::npos);
  }
  SECTION("kinetic energy from no source") {
    // Every particle at 2 m/s (well below the sound speed): 2 J/kg that nothing supplied.
    const auto bad = with([](HostSoil& s) {
      for (auto& v : s.vel) v = {2.0, 0, 0, v.w};
    });
    REQUIRE(bad);
    CHECK(bad->kind == "energy");
  }
  SECTION("particles lost through the floor") {
    const auto bad = with([](HostSoil& s) {
      s.pos[0].z = -0.02;
      s.vel[0].w = double(kParticleLost);
    });
    REQUIRE(bad);
    CHECK(bad->kind == "lost");
    CHECK(bad->message.find("below the bin's floor") != std::string::npos);
  }
  SECTION("lost within the tolerance of checks.max_lost_fraction") {
    nlohmann::json tolerant = j;
    tolerant["checks"] = {{"max_lost_fraction", 0.01}};  // 1 of 144 particles is 0.7 %
    CrmSolver s2(test::scene_from(tolerant), CrmDevice::kCpu);
    const CrmRunCheck h2(s2);
    HostSoil s = s2.soil();
    s.vel[0].w = double(kParticleLost);
    s2.restore(s, s2.bodies(), s2.time(), s2.steps());
    CHECK(!h2.check(s2));
  }
}

TEST_CASE("CRM run that fails keeps bodies.csv and says so in summary.json", "[highfi][crm]") {
  // A plate that sweeps the bed at 3 m/s throws soil over the bin's low walls; with no loss
  // tolerated, the run stops at the first particle lost.
  nlohmann::json j = test::bed_scene_json(kD0, kCells, 4, 0.0);
  j["bin"]["size"] = {kCells * kD0, kCells * kD0, 5 * kD0};
  j["bodies"] = {{{"name", "blade"},
                  {"shape", {{"type", "box"}, {"size", {0.01, 0.06, 0.03}}}},
                  {"position", {0.005, 0.03, 0.035}},
                  {"motion", {{"type", "prescribed"}, {"linear_velocity", {3, 0, 0}}}}}};
  j["duration"] = 0.02;
  j["checks"] = {{"max_lost_fraction", 0.0}};
  const CrmScene sc = test::scene_from(j);
  const auto out = std::filesystem::temp_directory_path() / "terracal_test_crm_failed_run";
  std::filesystem::remove_all(out);
  CrmRunOptions o;
  o.out = out;
  o.record_every = 1;
  std::string what;
  try {
    run_crm_scene(sc, o);
  } catch (const RunError& e) {
    what = e.what();
  }
  INFO(what);
  REQUIRE(!what.empty());
  CHECK(what.find("left the soil's room") != std::string::npos);
  CHECK(what.find("at t = ") != std::string::npos);
  const nlohmann::json summary = nlohmann::json::parse(std::ifstream(out / "summary.json"));
  CHECK(summary["status"] == "failed");
  CHECK(summary["failure"].get<std::string>().find("left the soil's room") != std::string::npos);
  std::ifstream csv(out / "bodies.csv");
  std::string line;
  long rows = -1;
  double last_time = 0;
  while (std::getline(csv, line)) {
    ++rows;
    if (rows > 0) last_time = std::stod(line.substr(0, line.find(',')));
  }
  CHECK(rows > 1);
  CHECK(last_time == Approx(summary["simulated_s"].get<double>()).margin(1e-9));
  CHECK(last_time < sc.duration);
  std::filesystem::remove_all(out);
}
