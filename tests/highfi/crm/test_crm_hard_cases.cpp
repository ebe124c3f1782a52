// Validation 13: hard cases, 20,000 steps each, no NaN or inf, and the kinetic energy settles.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <string>

#include "highfi/crm/crm_solver.hpp"
#include "tests/highfi/crm/crm_test_scenes.hpp"

using namespace terracal;

namespace {

constexpr long kSteps = 20000;

struct Outcome {
  SoilStats stats;
  double max_x = 0, top = 0;
  CrmSolver* solver = nullptr;
};

// The bed starts stress-free and stirred (random velocities up to `stir` m/s, or `kick` for every
// particle), so that it must find its equilibrium: a lattice with the lithostatic stress would
// already be at rest and prove nothing.
Outcome run(const nlohmann::json& j, const std::string& name, long steps = kSteps, double stir = 0.05,
            Vec3<double> kick = {}) {
  static std::unique_ptr<CrmSolver> keep;
  const CrmScene sc = test::scene_from(j);
  HostSoil bed = initial_bed(sc);
  for (std::size_t i = 0; i < bed.size(); ++i) {
    bed.s0[i] = {0, 0, 0, 0};
    bed.vel[i] = {kick.x + stir * std::sin(12.9898 * i), kick.y + stir * std::sin(78.233 * i),
                  kick.z + stir * std::sin(37.719 * i), 0};
  }
  keep = std::make_unique<CrmSolver>(sc, test::validation_device(), &bed);
  for (long k = 0; k < steps; ++k) keep->step();
  Outcome o;
  o.stats = keep->stats();
  o.solver = keep.get();
  const HostSoil s = keep->soil();
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.vel[i].w != double(kParticleLost)) {
      o.max_x = std::max(o.max_x, s.pos[i].x);
      o.top = std::max(o.top, s.pos[i].z);
    }
  std::printf(
      "%-28s %ld steps of %.3g s: nonfinite %ld, lost %ld, max speed %.3e m/s, KE %.3e J, front x %.4f, top %.4f\n",
      name.c_str(), steps, keep->time_step(), o.stats.nonfinite, o.stats.lost, o.stats.max_speed,
      o.stats.kinetic_energy, o.max_x, o.top);
  return o;
}

nlohmann::json small_bed() { return test::bed_scene_json(0.01, 8, 6); }

}  // namespace

TEST_CASE("CRM hard case: Moon gravity", "[highfi][crm][hard]") {
  nlohmann::json j = small_bed();
  j["soil"]["gravity"] = {0, 0, -1.62};
  const Outcome o = run(j, "Moon gravity");
  CHECK(o.stats.nonfinite == 0);
  CHECK(o.stats.max_speed < 1e-2);
}

TEST_CASE("CRM hard case: near-zero gravity", "[highfi][crm][hard]") {
  nlohmann::json j = small_bed();
  j["soil"]["gravity"] = {0, 0, -0.01};
  // A gentle stir: at 0.01 m/s^2 a particle thrown at 0.05 m/s would fly for 10 s.
  const Outcome o = run(j, "gravity 0.01 m/s^2", kSteps, 0.002);
  CHECK(o.stats.nonfinite == 0);
  CHECK(o.stats.max_speed < 1e-3);
}

TEST_CASE("CRM hard case: stiff soil at its CFL step", "[highfi][crm][hard]") {
  nlohmann::json j = small_bed();
  j["soil"]["young_modulus"] = 1e8;
  const Outcome o = run(j, "E = 1e8 Pa");
  CHECK(o.stats.nonfinite == 0);
  CHECK(o.stats.max_speed < 1e-2);
}

TEST_CASE("CRM hard case: a cohesive block stands, a dry one slumps", "[highfi][crm][hard]") {
  // A free-standing block 0.05 m wide and 0.06 m tall against the left wall of a 0.12 m bin.
  nlohmann::json j = test::bed_scene_json(0.01, 12, 6);
  j["bin"]["fill_length"] = 0.05;
  nlohmann::json wet = j;
  wet["soil"]["cohesion"] = 5000;
  wet["effects"] = {"artificial_viscosity", "cohesion"};
  const Outcome c = run(wet, "cohesive block c = 5 kPa", kSteps, 0.0);
  CHECK(c.stats.nonfinite == 0);
  CHECK(c.max_x < 0.05 + 0.01);  // the face has not moved by more than half a spacing beyond its particles
  CHECK(c.top > 0.06 - 0.01);
  CHECK(c.stats.max_speed < 1e-2);
  // The control: without cohesion the same block must slump (so the check above can fail).
  const Outcome d = run(j, "dry block (control)", 4000, 0.0);
  CHECK(d.stats.nonfinite == 0);
  CHECK(d.max_x > 0.05 + 0.02);
}

TEST_CASE("CRM hard case: a body dropped onto the bed at 2 m/s", "[highfi][crm][hard]") {
  nlohmann::json j = test::bed_scene_json(0.01, 10, 6);
  j["bin"]["size"] = {0.1, 0.1, 0.2};
  j["bodies"] = {{{"name", "box"},
                  {"shape", {{"type", "box"}, {"size", {0.04, 0.04, 0.02}}}},
                  {"position", {0.05, 0.05, 0.06 + 0.012 + 0.001}},
                  {"motion", {{"type", "dynamic"}, {"linear_velocity", {0, 0, -2}}}},
                  {"mass", 0.5},
                  {"inertia", {1e-4, 1e-4, 1e-4}}}};
  const Outcome o = run(j, "box dropped at 2 m/s", kSteps, 0.0);
  CHECK(o.stats.nonfinite == 0);
  // The impact's kinetic energy (0.5 kg at 2 m/s: 1 J) has been dissipated: under 1e-5 of it is left.
  const double body_ke = 0.5 * 0.5 * dot(o.solver->bodies()[0].velocity, o.solver->bodies()[0].velocity);
  CHECK(o.stats.kinetic_energy + body_ke < 1e-5);
  CHECK(norm(o.solver->bodies()[0].velocity) < 2e-2);
  CHECK(o.solver->bodies()[0].position.z < 0.073);  // it went into the soil and stayed
}

TEST_CASE("CRM hard case: particles that leave the bin are reported, not a crash", "[highfi][crm][hard]") {
  // The soil is thrown up and sideways at 2 m/s over the bin's low walls and falls out of the domain.
  nlohmann::json j = test::bed_scene_json(0.01, 8, 4);
  j["bin"]["size"] = {0.08, 0.08, 0.04};
  const Outcome o = run(j, "soil thrown out of the bin", 3000, 0.05, {2.0, 0.0, 2.0});
  CHECK(o.stats.nonfinite == 0);
  CHECK(o.stats.lost > 0);
  CHECK(o.stats.lost < long(o.solver->engine().soil_count()));  // some stayed in the bin
  CHECK(o.stats.max_speed < 5.0);
}
