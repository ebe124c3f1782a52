#pragma once
// The `deformable_terrain` effect's tire forces: a wheel-on-soil table (made by `terracal
// wheel-table` from SCM single-wheel runs) over load x longitudinal slip x slip angle, looked up
// where a reduced-order model would evaluate TMeasy. One source for the CPU and the GPU: the view
// holds plain pointers, into host memory (rom/terrain_table_h5.hpp owns them) or into one device
// allocation (rom_batch_cuda.cu).
//
// The table stores, per unit load, the gross thrust H = T / r (the torque that turns the wheel, over
// the table wheel's radius: a rigid wheel's normal stresses pass through its axle, so T is the
// shear's moment) and the motion resistance R = H - DP (compaction and bulldozing: what separates
// the thrust from the drawbar pull). A model turns its wheel against H r and pushes its chassis
// with H - R = DP, as the rig's wheel does. H at zero slip (the rut's shear on a rolling wheel) and
// R belong to a wheel that rolls: both fade in with the contact's speed (soil_contact_ramp), so a
// wheel at rest is neither pushed nor dragged.
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
  double slip_thrust = 0;  // H(s) - H(0): the thrust the slip adds, zero at zero slip [N]
  double thrust0 = 0;      // H(0): the thrust of a rolling wheel without slip [N]
  double fy = 0;           // lateral force [N] (only where the table has slip angles)
  double resistance = 0;   // motion resistance R >= 0 [N]
};

// The forces on one wheel under load fz at TMeasy's slips (sx, sy) (core/vehicle/tmeasy.hpp: the
// rig's s is sx, and tan(alpha) = -sy / (1 - sx)). Conventions, in docs/rom.md:
// - a table without negative slips mirrors its positive ones for braking: the gross thrust turns
//   round with the shear, H(-s) = -H(s) from the table's first slip s1 above zero on, linear from
//   H(0) at zero to -H(s1) in between; the resistance stays (docs/decisions.md, "ROM soft-soil forces");
// - the lateral force mirrors with the angle and is linear in it up to the first angle above zero;
// - loads, slips and angles beyond the table take its nearest entry, per unit load.
TERRACAL_HD_INLINE SoilTireForces soil_tire_forces(const TerrainTableView& tb, double fz, double sx, double sy) {
  SoilTireForces f;
  if (!(fz > 0)) return f;
  const bool mirror = tb.slip[0] >= 0;     // then slip[0] == 0 < slip[1] (the table's checks)
  const double u = mirror ? fabs(sx) : sx;  // the slip looked up
  const double tan_a = -sy / fmax(1.0 - sx, 1e-3);
  const double alpha = atan(fabs(tan_a));
  const bool small_angle = tb.has_lateral() && alpha < tb.angle[1];
  const TableSpot l = table_spot(tb.load, tb.n_load, fz);
  const TableSpot g = table_spot(tb.angle, tb.n_angle, alpha);
  const TableSpot s = table_spot(tb.slip, tb.n_slip, u);
  const double h0 = table_value(tb, tb.thrust, l, table_spot(tb.slip, tb.n_slip, 0.0), g);
  f.thrust0 = fz * h0;
  double h = table_value(tb, tb.thrust, l, s, g);
  if (mirror && sx < 0) {  // braking: the shear, and with it the thrust, reversed
    const double s1 = tb.slip[1];
    const double h1 = table_value(tb, tb.thrust, l, table_spot(tb.slip, tb.n_slip, s1), g);
    h = u >= s1 ? -h : h0 - (h0 + h1) * u / s1;
  }
  f.slip_thrust = fz * (h - h0);
  f.resistance = fz * fmax(table_value(tb, tb.resistance, l, s, g), 0.0);
  if (tb.has_lateral()) {
    const TableSpot g1 = small_angle ? table_spot(tb.angle, tb.n_angle, tb.angle[1]) : g;
    f.fy = (tan_a < 0 ? -1.0 : 1.0) * fz * table_value(tb, tb.lateral, l, s, g1) *
           (small_angle ? alpha / tb.angle[1] : 1.0);
  }
  return f;
}

// The contact speed [m/s] over which the zero-slip thrust and the resistance fade in: at rest the
// soil neither pushes nor drags; the half-implicit step stays stable (R / speed is a damping the
// chassis resolves at 1e-3 s).
inline constexpr double kSoilContactSpeed = 0.1;
TERRACAL_HD_INLINE double soil_contact_ramp(double vx) {
  const double r = vx / kSoilContactSpeed;
  return r > 1 ? 1.0 : r < -1 ? -1.0 : r;
}

// What a model takes from the table for one tire: the slip's thrust as TMeasy's steady stiffness
// (force over slip: the steady and the relaxed forms use it unchanged), ky where the table has slip
// angles (else TMeasy's lateral curve stays), and the zero-slip thrust and the resistance at the
// contact's speed vx along the wheel.
struct SoilContact {
  double thrust0 = 0;  // on the wheel and the chassis, along the wheel [N]
  double resist = 0;   // on the chassis only, along the wheel (against the travel) [N]
};
TERRACAL_HD_INLINE SoilContact soil_stiffness(const TerrainTableView& tb, double fz, double sx, double sy, double vx,
                                              double* kx, double* ky) {
  const double sx_eff = fabs(sx) > 1e-9 ? sx : 1e-9, sy_eff = fabs(sy) > 1e-9 ? sy : 1e-9;
  const SoilTireForces f = soil_tire_forces(tb, fz, sx_eff, sy_eff);
  *kx = f.slip_thrust / sx_eff;
  if (tb.has_lateral()) *ky = f.fy / sy_eff;
  const double ramp = soil_contact_ramp(vx);
  SoilContact c;
  c.thrust0 = f.thrust0 * ramp;
  c.resist = -f.resistance * ramp;
  return c;
}

}  // namespace terracal::rom
