// Validation 10: the angle of repose. A block of dry soil stands against the end wall of a bin;
// its other side, where a retaining wall stood, is free from the start (the wall is removed at
// t = 0). The block slumps and comes to rest; the slope of its free surface must lie within 5
// degrees of atan(mu_s). The angle is measured on the surface profile (the highest particle in
// each column, averaged across the bin's width) by a straight-line fit between 25 % and 75 % of the
// block's initial height, away from the rounded crest and the toe.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "highfi/crm/crm_solver.hpp"
#include "tests/highfi/crm/crm_test_scenes.hpp"

using namespace terracal;

namespace {

constexpr double kD0 = 0.01, kHeight = 0.2, kLength = 0.2;
constexpr int kColumnsX = 60, kColumnsY = 10;

// Surface angle [deg]: the highest particle of each column (d0 x d0), averaged across the width,
// fitted by a line over the columns whose surface lies between 25 % and 75 % of the block height.
double surface_angle(const HostSoil& soil, int* fitted) {
  std::vector<double> top(std::size_t(kColumnsX * kColumnsY), 0.0);
  for (std::size_t i = 0; i < soil.size(); ++i) {
    if (soil.vel[i].w == double(kParticleLost)) continue;
    const int ix = int(soil.pos[i].x / kD0), iy = int(soil.pos[i].y / kD0);
    if (ix < 0 || ix >= kColumnsX || iy < 0 || iy >= kColumnsY) continue;
    double& t = top[std::size_t(ix + kColumnsX * iy)];
    t = std::max(t, soil.pos[i].z + 0.5 * kD0);
  }
  double n = 0, sx = 0, sz = 0, sxx = 0, sxz = 0;
  for (int ix = 0; ix < kColumnsX; ++ix) {
    double z = 0;
    for (int iy = 0; iy < kColumnsY; ++iy) z += top[std::size_t(ix + kColumnsX * iy)];
    z /= kColumnsY;
    if (z < 0.25 * kHeight || z > 0.75 * kHeight) continue;
    const double x = (ix + 0.5) * kD0;
    n += 1;
    sx += x;
    sz += z;
    sxx += x * x;
    sxz += x * z;
  }
  *fitted = int(n);
  if (n < 3) return 0;
  const double b = (n * sxz - sx * sz) / (n * sxx - sx * sx);
  return std::atan(-b) * 180.0 / M_PI;
}

struct Slope {
  double angle_deg = 0, earlier_angle_deg = 0, kinetic_energy = 0, peak_energy = 0;
  int fitted = 0;
  long lost = 0, nonfinite = 0;
};

Slope slump(double mu_s) {
  nlohmann::json j = test::bed_scene_json(kD0, kColumnsX, int(kHeight / kD0));
  j["soil"]["mu_s"] = mu_s;
  j["soil"]["mu_2"] = mu_s;
  j["bin"]["size"] = {kColumnsX * kD0, kColumnsY * kD0, kHeight + 0.04};
  j["bin"]["fill_length"] = kLength;
  j["resolution"]["cpu_precision"] = "float";
  CrmSolver s(test::scene_from(j), test::validation_device());
  Slope r;
  // The collapse is over within about 0.4 s and the kinetic energy is below 1/500 of its peak by 0.7 s;
  // the angle is read at 0.7 s and again at 0.9 s (it moved by under 0.3 degrees between them, and by
  // under 0.6 degrees from 0.9 s to 1.2 s, at both friction coefficients).
  auto run_to = [&](double t) {
    while (s.time() < t) {
      s.step();
      if (s.steps() % 100 == 0) r.peak_energy = std::max(r.peak_energy, s.stats().kinetic_energy);
    }
  };
  int fitted = 0;
  run_to(0.7);
  r.earlier_angle_deg = surface_angle(s.soil(), &fitted);
  run_to(0.9);
  r.angle_deg = surface_angle(s.soil(), &r.fitted);
  const SoilStats st = s.stats();
  r.kinetic_energy = st.kinetic_energy;
  r.lost = st.lost;
  r.nonfinite = st.nonfinite;
  std::printf(
      "slump mu_s=%.2f: surface slope %.1f deg (%.1f deg at 0.7 s) against atan(mu_s) = %.1f deg, %d columns "
      "fitted; kinetic energy %.3g J (peak %.3g J)\n",
      mu_s, r.angle_deg, r.earlier_angle_deg, std::atan(mu_s) * 180.0 / M_PI, r.fitted, r.kinetic_energy,
      r.peak_energy);
  return r;
}

}  // namespace

TEST_CASE("CRM: a released block comes to rest at the angle of repose", "[highfi][crm]") {
  // Two friction coefficients, so that the angle is shown to follow mu_s rather than to sit near 35 degrees by chance.
  for (double mu_s : {0.5, 0.7}) {
    const Slope r = slump(mu_s);
    CHECK(r.nonfinite == 0);
    CHECK(r.lost == 0);
    CHECK(r.fitted >= 5);
    CHECK(r.kinetic_energy < 5e-3 * r.peak_energy);  // nearly at rest ...
    // ... and the slope no longer changes: within 1 degree over the last part of the run (0.2 degrees
    // at both friction coefficients)
    CHECK(std::abs(r.angle_deg - r.earlier_angle_deg) < 1.0);
    CHECK(std::abs(r.angle_deg - std::atan(mu_s) * 180.0 / M_PI) < 5.0);
  }
}
