// Strongly compressed soil and the run's health checks: soil squeezed in a closed box keeps its
// mass (its density follows the volume, its pressure the density), and a run that goes bad is
// named as such, with the time, the place and what to try.
#include <catch2/catch.hpp>

#include <algorithm>
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
#include "highfi/crm/soil_model.hpp"
#include "tests/highfi/crm/crm_test_scenes.hpp"

using namespace terracal;

namespace {

constexpr double kD0 = 0.01;
constexpr int kCells = 6;  // the box is 6 x 6 spacings, filled 6 deep

// The squeeze scene's soil and effects (studies/crm/squeeze: the 2022 soil with 1000 Pa cohesion,
// the rigs' effects, h/d0 1.4) in a box 6 spacings wide, under a lid as wide as the box, resting
// on the soil and driven down at 0.1 m/s for `duration` seconds.
nlohmann::json closed_box(double duration) {
  nlohmann::json j = test::bed_scene_json(kD0, kCells, kCells, 0.0);
  j["soil"]["cohesion"] = 1000;
  j["effects"] = {"artificial_viscosity", "cohesion", "hourglass_damping", "hourglass_stiffness"};
  j["hourglass_damping"] = {{"alpha", 0.4}};
  j["hourglass_stiffness"] = {{"beta", 0.03}};
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

// Runs the scene with the run checks every kCrmCheckEvery steps; returns the first failure's
// message, empty when the run stays sound to the end.
std::string squeeze(CrmSolver& solver, double duration) {
  const CrmRunCheck health(solver);
  while (solver.time() < duration - 0.5 * solver.time_step()) {
    solver.step();
    if (solver.steps() % kCrmCheckEvery == 0)
      if (const auto bad = health.check(solver)) return bad->message;
  }
  return {};
}

}  // namespace

TEST_CASE("CRM density cap: fixed at ordinary pressures, tied to the pressure under very high ones", "[highfi][crm]") {
  // The 2022 soil: rho0 1700 kg/m^3, K = E / (3 (1 - 2 nu)) with E 1 MPa, nu 0.3.
  SoilModel<double> m;
  m.rho0 = 1700;
  m.bulk_modulus = 1e6 / (3 * (1 - 2 * 0.3));
  const double K = m.bulk_modulus, fixed = 1.5 * m.rho0;
  // No pressure, tension (a stress-free or zeroed particle) and a wheel's contact (p/K ~ 0.05-0.1):
  // the fixed bound. A cap that loosens with any pressure (1.5 rho0 exp(p/K), 1.66 rho0 at p/K 0.1)
  // let the CRM wheel keep sinking (docs/decisions.md, "Density cap").
  CHECK(density_cap(0.0, m) == fixed);
  CHECK(density_cap(-1e4, m) == fixed);
  CHECK(density_cap(0.1 * K, m) == fixed);
  CHECK(density_cap(0.2 * K, m) == fixed);
  // Continuous where the tie takes over (p/K = ln 1.25).
  CHECK(density_cap(std::log(1.25) * K, m) == Approx(fixed).epsilon(1e-12));
  // Soil under a plate driven towards the floor (p/K ~ 1.2): the density may follow its pressure,
  // rho0 exp(p/K) = 3.3 rho0, with a fifth to spare.
  const double tie = m.rho0 * std::exp(1.2);
  CHECK(density_cap(1.2 * K, m) == Approx(1.2 * tie).epsilon(1e-12));
  CHECK(density_cap(1.2 * K, m) > tie);
  // The GPU's float32 reads the same bound.
  SoilModel<float> mf;
  mf.rho0 = 1700;
  mf.bulk_modulus = float(K);
  CHECK(density_cap(0.1f * mf.bulk_modulus, mf) == Approx(fixed).epsilon(1e-6));
  CHECK(density_cap(1.2f * mf.bulk_modulus, mf) == Approx(1.2 * tie).epsilon(1e-5));
}

TEST_CASE("CRM: soil squeezed to half its volume in a closed box stays in the box", "[highfi][crm][hard]") {
  // The lid goes down 0.03 m of the 0.06 m: the soil reaches p/K ~ 0.5, as under a plate driven
  // towards the floor. Every particle stays in the box under the lid, the pressure
  // follows the density (p = K ln(rho / rho0) from a bed at rest without stress, the tie the density's
  // cap keeps), and no particle is pushed into the lid, with the walls' contact pressure
  // (resolution.wall_contact 30). Without it (the default, 0) the particles under the lid close in
  // on its markers as the pressure grows and are pushed through it at V0/V ~ 1.3
  // (results/crm_squeeze).
  const double duration = 0.3;
  nlohmann::json j = closed_box(duration);
  SECTION("without the walls' contact pressure (the default), soil is pushed through the lid") {
    const CrmScene sc = test::scene_from(j);
    HostSoil bed = initial_bed(sc);
    for (auto& s : bed.s0) s = {0, 0, 0, 0};
    CrmSolver solver(sc, test::validation_device(), &bed);
    const std::string failure = squeeze(solver, duration);
    const double lid_bottom = solver.bodies()[0].position.z - 0.01;
    std::printf("closed box without wall contact: stopped at V0/V = %.3f: %s\n", 0.06 / lid_bottom, failure.c_str());
    CHECK(!failure.empty());
    CHECK(0.06 / lid_bottom < 1.5);
  }
  SECTION("with it, the soil stays in the box") {
    j["resolution"]["wall_contact"] = 30;
    const CrmScene sc = test::scene_from(j);
    HostSoil bed = initial_bed(sc);
    for (auto& s : bed.s0) s = {0, 0, 0, 0};
    CrmSolver solver(sc, test::validation_device(), &bed);
    const std::string failure = squeeze(solver, duration);
    INFO(failure);
    REQUIRE(failure.empty());
    const HostSoil s = solver.soil();
    const double size = kCells * kD0, m = sc.soil.density * kD0 * kD0 * kD0, K = sc.soil.bulk_modulus();
    const double lid_bottom = solver.bodies()[0].position.z - 0.01;
    double volume = 0, p_sum = 0, tie_sum = 0, highest = 0;
    double past = -1;
    for (std::size_t i = 0; i < s.size(); ++i) {
      volume += m / s.pos[i].w;
      p_sum += -(s.s0[i].x + s.s0[i].y + s.s0[i].z) / 3;
      tie_sum += K * std::log(s.pos[i].w / sc.soil.density);
      highest = std::max(highest, s.pos[i].z);
      const Vec4<double>& x = s.pos[i];
      // How far past the box's walls (floor, sides, lid) the particle's centre lies.
      past = std::max({past, -x.x, x.x - size, -x.y, x.y - size, -x.z, x.z - lid_bottom});
    }
    const double box = size * size * lid_bottom, n = double(s.size());
    std::printf(
        "closed box: lid at %.4f m (V0/V = %.3f), soil volume %.4g m^3 against %.4g m^3 under the lid; mean p %.4g "
        "Pa, K ln(rho/rho0) %.4g Pa; highest particle %.2f spacings above the lid's bottom, the farthest %.2f "
        "spacings past a wall\n",
        lid_bottom, size / lid_bottom, volume, box, p_sum / n, tie_sum / n, (highest - lid_bottom) / kD0, past / kD0);
    CHECK(lid_bottom == Approx(0.03).margin(1e-5));
    CHECK(solver.stats().lost == 0);
    // Every particle's centre stays inside the walls' surfaces (0.16 spacings inside, measured).
    CHECK(past < 0);
    CHECK(highest < lid_bottom);
    CHECK(p_sum / n == Approx(tie_sum / n).epsilon(0.1));
    // The density integrates the SPH divergence, which falls short of the lattice's compression once
    // the lattice is this anisotropic (spacing halved vertically, unchanged across): sum m / rho
    // exceeds the box by 20 % here (3.6 % at V0/V = 1.2).
    CHECK(volume == Approx(box).epsilon(0.25));
  }
}

TEST_CASE("CRM soil statistics count the particles held at the density cap", "[highfi][crm]") {
  // A bed at rest after 20 steps has none; particles set to the cap of their own pressure (stress-free: 1.5 rho0;
  // under p = K: 1.2 rho0 e) are counted, on either backend, and frozen ones are not.
  nlohmann::json j = test::bed_scene_json(kD0, kCells, 4, 0.0);
  const CrmScene sc = test::scene_from(j);
  CrmSolver solver(sc, test::validation_device());
  for (int k = 0; k < 20; ++k) solver.step();
  CHECK(solver.stats().at_density_cap == 0);
  HostSoil s = solver.soil();
  const double rho0 = sc.soil.density, K = sc.soil.bulk_modulus();
  s.pos[3].w = 1.5 * rho0;
  s.s0[3] = {0, 0, 0, 0};
  s.pos[5].w = 1.2 * rho0 * std::exp(1.0);
  s.s0[5] = {-K, -K, -K, 0};
  s.pos[7].w = 1.4 * rho0;  // below the cap: not counted
  s.s0[7] = {0, 0, 0, 0};
  s.pos[9].w = 1.5 * rho0;  // at the cap but frozen (outside the active domain): not counted
  s.s0[9] = {0, 0, 0, 0};
  s.vel[9] = {0, 0, 0, double(kParticleFrozen)};
  solver.restore(s, solver.bodies(), solver.time(), solver.steps());
  CHECK(solver.stats().at_density_cap == 2);
  CHECK(solver.stats().frozen == 1);
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
