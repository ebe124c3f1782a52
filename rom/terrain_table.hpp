#pragma once
// The `deformable_terrain` effect's tire forces: a wheel-on-soil table (made by `terracal
// wheel-table` from SCM single-wheel runs) over load x longitudinal slip x slip angle, looked up
// where a reduced-order model would evaluate TMeasy. One source for the CPU and the GPU: the view
// holds plain pointers, into host memory (rom/terrain_table_h5.hpp owns them) or into one device
// allocation (rom_batch_cuda.cu).
//
// The table stores, per unit load, the gross thrust H = T / r (the torque the drive needs, over
// the table wheel's radius), the motion resistance R = H - DP (compaction and bulldozing: what
// separates the thrust from the drawbar pull) and the lateral force. The models apply H as the
// tire's longitudinal force and R r as a resisting torque on the wheel's spin, the dry-friction
// bound that rolling resistance and brakes use: a wheel at rest under load is held, never pushed,
// and a rolling wheel pays R through its slip.
#include <cmath>

#include "core/host_device.hpp"

namespace terracal::rom {

struct TerrainTableView {
  int n_load = 0, n_slip = 0, n_angle = 0;
  const double* load = nullptr;   // [N] per wheel, increasing
  const double* slip = nullptr;   // longitudinal slip s = 1 - v / (omega r), increasing
  const double* angle = nullptr;  // slip angles [rad], increasing from 0
  // [n_load][n_slip][n_angle], per unit load: gross thrust H/Fz, resistance R/Fz, lateral Fy/Fz.
  const double* thrust = nullptr;
  const double* resistance = nullptr;
  const double* lateral = nullptr;
  double radius = 0;  // the table wheel's radius [m]
  TERRACAL_HD bool present() const { return n_load > 0; }
  TERRACAL_HD bool has_lateral() const { return n_angle > 1; }
};

// Where v falls on the increasing axis x[0..n): the lower index and the weight of the upper one,
// clamped to the ends (a value outside the table takes the nearest entry).
struct TableSpot {
  int i = 0;
  double t = 0;
};
TERRACAL_HD_INLINE TableSpot table_spot(const double* x, int n, double v) {
  TableSpot p;
  if (n < 2 || !(v > x[0])) return p;  // also NaN: the first entry
  if (v >= x[n - 1]) {
    p.i = n - 2;
    p.t = 1;
    return p;
  }
  while (p.i < n - 2 && v >= x[p.i + 1]) ++p.i;
  p.t = (v - x[p.i]) / (x[p.i + 1] - x[p.i]);
  return p;
}

// Trilinear interpolation of one [load][slip][angle] array.
TERRACAL_HD_INLINE double table_value(const TerrainTableView& tb, const double* a, TableSpot l, TableSpot s,
                                      TableSpot g) {
  double out = 0;
  for (int dl = 0; dl < 2; ++dl) {
    const double wl = dl ? l.t : 1 - l.t;
    if (wl == 0 || l.i + dl >= tb.n_load) continue;
    for (int ds = 0; ds < 2; ++ds) {
      const double ws = ds ? s.t : 1 - s.t;
      if (ws == 0 || s.i + ds >= tb.n_slip) continue;
      for (int dg = 0; dg < 2; ++dg) {
        const double wg = dg ? g.t : 1 - g.t;
        if (wg == 0 || g.i + dg >= tb.n_angle) continue;
        out += wl * ws * wg * a[((l.i + dl) * tb.n_slip + s.i + ds) * tb.n_angle + g.i + dg];
      }
    }
  }
  return out;
}

struct SoilTireForces {
  double fx = 0;          // gross thrust on the wheel, wheel frame [N]
  double fy = 0;          // lateral force [N] (only where the table has slip angles)
  double resistance = 0;  // motion resistance R >= 0 [N], applied as R r against the spin
};

// The forces on one wheel under load fz at TMeasy's slips (sx, sy) (core/vehicle/tmeasy.hpp: the
// rig's s is sx, and tan(alpha) = -sy / (1 - sx)). Conventions, in docs/rom.md:
// - the thrust is taken as zero at zero slip and linear up to the table's first slip either side,
//   so a wheel without slip (at standstill too) gets no push; the lateral force likewise up to the
//   first slip angle above zero;
// - a table without negative slips mirrors its positive ones (H(-s) = -H(s), same resistance);
// - slip angles mirror (Fy(-alpha) = -Fy(alpha)); loads, slips and angles beyond the table take its
//   nearest entry, forces stay proportional to the load.
TERRACAL_HD_INLINE SoilTireForces soil_tire_forces(const TerrainTableView& tb, double fz, double sx, double sy) {
  SoilTireForces f;
  if (!(fz > 0)) return f;
  const bool mirror = tb.slip[0] >= 0;
  const double u = mirror ? fabs(sx) : sx;  // the slip looked up
  const double sign = mirror && sx < 0 ? -1.0 : 1.0;
  // The table's slip nearest zero on u's side (the reader asks for one above zero).
  int k = 0;
  if (u >= 0) {
    while (k < tb.n_slip - 1 && tb.slip[k] <= 0) ++k;
  } else {
    k = tb.n_slip - 1;
    while (k > 0 && tb.slip[k] >= 0) --k;
  }
  const double s_near = tb.slip[k];
  const bool linear = fabs(u) < fabs(s_near) && (u < 0) == (s_near < 0);
  const double tan_a = -sy / fmax(1.0 - sx, 1e-3);
  const TableSpot l = table_spot(tb.load, tb.n_load, fz);
  // Likewise the lateral force is linear in the angle up to the table's first angle above zero.
  const double alpha = atan(fabs(tan_a));
  const bool small_angle = tb.has_lateral() && alpha < tb.angle[1];
  const TableSpot g = table_spot(tb.angle, tb.n_angle, small_angle ? tb.angle[1] : alpha);
  const TableSpot s = table_spot(tb.slip, tb.n_slip, u);
  const double thrust = linear ? table_value(tb, tb.thrust, l, table_spot(tb.slip, tb.n_slip, s_near), g) * u / s_near
                               : table_value(tb, tb.thrust, l, s, g);
  f.fx = fz * sign * thrust;
  const TableSpot g_true = small_angle ? table_spot(tb.angle, tb.n_angle, alpha) : g;
  f.resistance = fz * fmax(table_value(tb, tb.resistance, l, s, g_true), 0.0);
  if (tb.has_lateral())
    f.fy = (tan_a < 0 ? -1.0 : 1.0) * fz * table_value(tb, tb.lateral, l, s, g) * (small_angle ? alpha / tb.angle[1] : 1.0);
  return f;
}

// The table's forces as TMeasy's steady stiffnesses (force over slip), so that the steady and the
// relaxed tire forms use them unchanged: kx, and ky where the table has slip angles (else TMeasy's
// lateral curve stays). Returns the motion resistance [N].
TERRACAL_HD_INLINE double soil_stiffness(const TerrainTableView& tb, double fz, double sx, double sy, double* kx,
                                         double* ky) {
  const double sx_eff = fabs(sx) > 1e-9 ? sx : 1e-9, sy_eff = fabs(sy) > 1e-9 ? sy : 1e-9;
  const SoilTireForces f = soil_tire_forces(tb, fz, sx_eff, sy_eff);
  *kx = f.fx / sx_eff;
  if (tb.has_lateral()) *ky = f.fy / sy_eff;
  return f.resistance;
}

}  // namespace terracal::rom
