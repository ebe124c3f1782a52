// The particle lattice under its own weight (highfi/crm/lattice_stability.hpp, results/crm_settling):
// - the linear analysis: with the Wendland C2 kernel the lattice has modes that a compressive stress
//   drives (h/d0 1.2 and 1.3) and none at 1.4, for any compression;
// - the solver follows the analysis: a column mode (columns of particles alternating up and down
//   along x and y, which the velocity gradient does not see) seeded into a lithostatic bed grows as
//   cosh(s t) at h/d0 = 1.2, with s the analysis' rate at each particle's depth, and stays put at 1.4;
// - a scene at an unstable h/d0 is still accepted (it is a fidelity knob), the default is 1.4.
// No artificial viscosity in the beds: only the terms of the analysis act on the mode.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <map>

#include "highfi/crm/crm_solver.hpp"
#include "highfi/crm/lattice_stability.hpp"
#include "tests/highfi/crm/crm_test_scenes.hpp"

using namespace terracal;

namespace {

constexpr double kD0 = 0.05;
constexpr int kCells = 20;   // 1 x 1 m
constexpr int kLayers = 30;  // 1.5 m deep: 12000 particles

struct Soil {
  double rho = 1700, E = 1e6, nu = 0.3, g = 9.81;
  double mu() const { return E / (2 * (1 + nu)); }
  double lambda() const { return E * nu / ((1 + nu) * (1 - 2 * nu)); }
  double k0() const { return nu / (1 - nu); }
  // The lithostatic stress at `depth`, as settling starts from (crm_solver.cpp).
  std::array<double, 3> stress(double depth) const {
    const double szz = -rho * g * depth;
    return {k0() * szz, k0() * szz, szz};
  }
};

LatticeStability stability(double h_over_d0, double depth, KernelType kernel = KernelType::kWendlandC2) {
  const Soil s;
  return lattice_stability(kernel, h_over_d0, kD0, s.rho, s.lambda(), s.mu(), s.stress(depth));
}

// omega^2 of the z-polarised column mode k d0 = (pi, pi, 0) at `depth` (negative: growth rate squared).
double column_omega2(double h_over_d0, double depth) {
  const Soil s;
  return lattice_mode_omega2(KernelType::kWendlandC2, h_over_d0, kD0, s.rho, s.lambda(), s.mu(), s.stress(depth),
                             {1, 1, 0})[2][2];
}

int parity(const Vec4<double>& p) {
  const int ix = int(std::lround(p.x / kD0 - 0.5)), iy = int(std::lround(p.y / kD0 - 0.5));
  return (ix + iy) % 2 == 0 ? 1 : -1;
}

struct ModeRun {
  double measured = 0, predicted = 0;  // mode amplitude after the run over its start
};

// Seeds the column mode (v_z = A parity) into the lithostatic bed, runs `steps` steps and compares
// the mode's amplitude among particles 4 h from the walls, the floor and the surface with the mean
// over the same particles of cosh(s t) (unstable) or cos(omega t) (stable) at each one's depth.
ModeRun column_mode(double h_over_d0, int steps) {
  nlohmann::json j = test::bed_scene_json(kD0, kCells, kLayers, 0);
  j["resolution"]["h_over_d0"] = h_over_d0;
  j["effects"] = nlohmann::json::array();
  const CrmScene sc = test::scene_from(j);
  constexpr double kAmplitude = 1e-4;
  HostSoil bed = initial_bed(sc);
  for (std::size_t i = 0; i < bed.size(); ++i) bed.vel[i] = {0, 0, kAmplitude * parity(bed.pos[i]), bed.vel[i].w};
  CrmSolver solver(sc, test::validation_device(), &bed);
  for (int k = 0; k < steps; ++k) solver.step();
  const double t = steps * sc.numerics.time_step, margin = 4 * sc.numerics.smoothing_length(), top = kLayers * kD0;
  const HostSoil end = solver.soil();
  ModeRun r;
  long n = 0;
  std::map<long, double> omega2_of_layer;
  for (std::size_t i = 0; i < end.size(); ++i) {
    const Vec4<double>& p = end.pos[i];
    if (p.x < margin || p.x > kCells * kD0 - margin || p.y < margin || p.y > kCells * kD0 - margin || p.z < margin ||
        p.z > top - margin)
      continue;
    // One analysis per lattice layer (particles have moved by micrometres from their sites).
    const long layer = std::lround((top - p.z) / kD0 - 0.5);
    auto it = omega2_of_layer.find(layer);
    if (it == omega2_of_layer.end())
      it = omega2_of_layer.emplace(layer, column_omega2(h_over_d0, (layer + 0.5) * kD0)).first;
    const double w2 = it->second;
    r.measured += parity(p) * end.vel[i].z / kAmplitude;
    r.predicted += w2 < 0 ? std::cosh(std::sqrt(-w2) * t) : std::cos(std::sqrt(w2) * t);
    ++n;
  }
  REQUIRE(n > 500);
  r.measured /= double(n);
  r.predicted /= double(n);
  std::printf(
      "column mode, h/d0 %.2g, after %.4g s (%d steps, %ld particles): amplitude %.4f of its start, predicted %.4f\n",
      h_over_d0, t, steps, n, r.measured, r.predicted);
  return r;
}

}  // namespace

TEST_CASE("CRM lattice: the Wendland C2 lattice is unstable under compression at h/d0 1.2 and 1.3, stable at 1.4",
          "[highfi][crm]") {
  for (double depth : {0.5, 1.4, 3.0, 10.0}) {
    const LatticeStability a = stability(1.2, depth), b = stability(1.3, depth), c = stability(1.4, depth);
    std::printf(
        "depth %.3g m: growth %.1f 1/s at k d0/pi = (%.2g, %.2g, %.2g) (h/d0 1.2), %.1f (1.3), %.3g (1.4); "
        "smallest geometric stiffness %.4f / %.4f / %.5f\n",
        depth, a.growth_rate, a.wave[0], a.wave[1], a.wave[2], b.growth_rate, c.growth_rate, a.min_geometric,
        b.min_geometric, c.min_geometric);
    CHECK(a.growth_rate > 10);
    CHECK(b.growth_rate > 5);
    CHECK(c.growth_rate == 0);
    // The growth is the stress's: the rate goes as sqrt(depth) once the stress dominates.
    CHECK(a.min_geometric < -0.1);
  }
  CHECK(stability(1.4, 1.0).min_geometric > -1e-9);  // no mode with negative geometric stiffness at all
  // Without stress the elastic term alone acts: stable at any h/d0.
  CHECK(stability(1.2, 0).growth_rate == 0);
  // The cubic spline at 1.2 is unstable too.
  CHECK(stability(1.2, 1.4, KernelType::kCubicSpline).growth_rate > 10);
  // The column mode is the fastest at 1.2, and it grows as the square root of the stress.
  const LatticeStability a = stability(1.2, 1.4);
  CHECK(a.wave[0] == 1);
  CHECK(a.wave[1] == 1);
  CHECK(a.wave[2] == 0);
  CHECK(stability(1.2, 5.6).growth_rate == Approx(2 * a.growth_rate).epsilon(1e-6));
}

TEST_CASE("CRM lattice: a column mode grows in a lithostatic bed at the analysed rate at h/d0 1.2, not at 1.4",
          "[highfi][crm]") {
  const ModeRun unstable = column_mode(1.2, 100), stable = column_mode(1.4, 100);
  CHECK(unstable.predicted > 3);  // the check below is not trivially met
  CHECK(unstable.measured == Approx(unstable.predicted).epsilon(0.05));
  CHECK(stable.predicted <= 1.0);  // an oscillation, cos(omega t): the geometric stiffness restores the mode
  CHECK(stable.measured == Approx(stable.predicted).margin(0.05));
}

TEST_CASE("CRM lattice: scenes default to h/d0 1.4 and still accept 1.2", "[highfi][crm]") {
  nlohmann::json j = test::bed_scene_json(kD0, kCells, kLayers, 0);
  j["resolution"].erase("h_over_d0");
  CHECK(test::scene_from(j).numerics.h_over_d0 == 1.4);
  j["resolution"]["h_over_d0"] = 1.2;
  CHECK(test::scene_from(j).numerics.h_over_d0 == 1.2);  // a warning, not an error: it is a fidelity knob
}
