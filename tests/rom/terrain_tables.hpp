#pragma once
// Wheel tables made from formulas, for the deformable_terrain tests that need no SCM runs: a
// Janosi-like thrust H/Fz = h0 + mu (1 - exp(-s / s0)), a resistance R/Fz = r0 + r1 s and a lateral
// force Fy/Fz = -mu_y (1 - exp(-alpha / a0)), tabulated as the rig's DBP, torque and lateral force.
#include <cmath>
#include <vector>

#include "rom/terrain_table_h5.hpp"

namespace terracal::rom::testing {

struct TableFormula {
  double h0 = 0, mu = 0.7, s0 = 0.05, r0 = 0.05, r1 = 0.1, mu_y = 0.6, a0 = 0.05, radius = 0.47;
  double thrust(double s) const { return h0 + mu * (1 - std::exp(-s / s0)); }
  double resistance(double s) const { return r0 + r1 * s; }
  double lateral(double a) const { return -mu_y * (1 - std::exp(-a / a0)); }
};

inline TerrainTable formula_table(const TableFormula& f = {}, std::vector<double> loads = {2000, 4000, 8000},
                                  std::vector<double> slips = {0, 0.02, 0.05, 0.1, 0.2, 0.4, 0.8},
                                  std::vector<double> angles = {0, 0.05, 0.1, 0.2}) {
  TerrainTable t;
  t.load = std::move(loads);
  t.slip = std::move(slips);
  t.angle = std::move(angles);
  t.radius = f.radius;
  t.width = 0.25;
  t.duration = 1;
  t.soil = "formula";
  t.wheel = "formula";
  for (double fz : t.load)
    for (double s : t.slip)
      for (double a : t.angle) {
        const double h = fz * f.thrust(s);
        t.torque.push_back(h * f.radius);
        t.dbp.push_back(h - fz * f.resistance(s));
        t.sinkage.push_back(0.01);
        t.lateral.push_back(fz * f.lateral(a));
      }
  finish_coefficients(t);
  return t;
}

}  // namespace terracal::rom::testing
