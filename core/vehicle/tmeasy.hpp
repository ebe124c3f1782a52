#pragma once
// The TMeasy tire (G. Rill, "Road Vehicle Dynamics", 2011, ch. 3; Rill, "TMeasy 6", 2019): steady
// longitudinal and lateral force curves given at the nominal load and twice that load, combined slip
// by normalised slips, and a first-order (relaxation) form that stays finite at standstill. Written
// once for the CPU and the GPU; parameters are plain structs.
#include <cmath>

#include "core/host_device.hpp"

namespace terracal {

// One direction's steady force curve: initial slope df0 [N], maximum fm [N] at slip sm, sliding
// force fs [N] from slip ss on.
struct TmeasyCurve {
  double df0 = 0, fm = 0, sm = 0, fs = 0, ss = 0;
};

struct TmeasyParams {
  double unloaded_radius = 0;           // r0 [m]
  double wheel_inertia = 0;             // [kg m^2], wheel and tire about the spin axis
  double vertical_stiffness = 0;        // [N/m], static radius r0 - Fz / kt
  double rolling_resistance = 0;        // coefficient [-]: torque rr * Fz * rdyn against the spin
  double nominal_load = 0;              // Fzn [N]; curves are given at Fzn and 2 Fzn
  double max_load = 0;                  // loads beyond this use the curve at this load [N]
  double longitudinal_stiffness = 0;    // tread stiffness cx [N/m] of the relaxation form
  double lateral_stiffness = 0;         // cy [N/m]
  double longitudinal_damping = 0;      // dx [N s/m]
  double lateral_damping = 0;           // dy [N s/m]
  double rdyn_coefficient[2] = {0, 0};  // lambda at Fzn, 2 Fzn: rdyn = lambda r0 + (1 - lambda) rstatic
  TmeasyCurve x[2];                     // longitudinal curve at Fzn, 2 Fzn
  TmeasyCurve y[2];                     // lateral curve at Fzn, 2 Fzn
};

// Slip velocities below this do not divide by zero: the slips' denominator is rdyn |omega| + this.
inline constexpr double kTmeasySlipVelocity = 0.01;  // [m/s]

// Rill's load interpolation: forces quadratic in Fz through (0, 0), (Fzn, p1), (2 Fzn, p2);
// slips linear through (Fzn, s1), (2 Fzn, s2).
TERRACAL_HD_INLINE double tmeasy_force_at_load(double q, double p1, double p2) {
  return q * (2.0 * p1 - 0.5 * p2 - (p1 - 0.5 * p2) * q);
}
TERRACAL_HD_INLINE double tmeasy_slip_at_load(double q, double s1, double s2) { return s1 + (s2 - s1) * (q - 1.0); }

TERRACAL_HD_INLINE TmeasyCurve tmeasy_curve_at_load(const TmeasyCurve c[2], double q) {
  TmeasyCurve r;
  r.df0 = tmeasy_force_at_load(q, c[0].df0, c[1].df0);
  r.fm = tmeasy_force_at_load(q, c[0].fm, c[1].fm);
  r.fs = tmeasy_force_at_load(q, c[0].fs, c[1].fs);
  r.sm = tmeasy_slip_at_load(q, c[0].sm, c[1].sm);
  r.ss = tmeasy_slip_at_load(q, c[0].ss, c[1].ss);
  return r;
}

// The curve's force at slip s >= 0 divided by s (finite at s = 0: the initial slope).
TERRACAL_HD_INLINE double tmeasy_force_over_slip(const TmeasyCurve& c, double s) {
  if (s <= c.sm) {
    const double sigma = s / c.sm;
    return c.df0 / (1.0 + sigma * (sigma + c.df0 * c.sm / c.fm - 2.0));
  }
  if (s < c.ss) {
    const double sigma = (s - c.sm) / (c.ss - c.sm);
    return (c.fm - (c.fm - c.fs) * sigma * sigma * (3.0 - 2.0 * sigma)) / s;
  }
  return c.fs / s;
}

// Both directions at one load, with the combined-slip normalisation of Rill.
struct TmeasyLoadState {
  TmeasyCurve x, y;
  double sx_hat = 1, sy_hat = 1;  // normalising slips
  double rdyn = 0;                // dynamic rolling radius [m]
};

// `friction` scales the maximum and sliding forces: a road with a friction coefficient that
// fraction of the one the curves were measured on.
TERRACAL_HD_INLINE TmeasyLoadState tmeasy_at_load(const TmeasyParams& p, double fz, double friction = 1.0) {
  TmeasyLoadState st;
  const double fz_c = min_of(max_of(fz, 0.0), p.max_load);
  const double q = fz_c / p.nominal_load;
  // At zero load the curves vanish; a tiny load keeps the ratios below finite.
  const double qs = max_of(q, 1e-6);
  st.x = tmeasy_curve_at_load(p.x, qs);
  st.y = tmeasy_curve_at_load(p.y, qs);
  // Where the load extrapolation makes the initial slope too small for a curve that is concave from
  // zero slip, it is lifted to 2 fm / sm (as Chrono and LFDM do). (Compared without dividing: this
  // runs four times per step per vehicle, and divisions are its cost.)
  if (st.x.df0 * st.x.sm < 2.0 * st.x.fm) st.x.df0 = 2.0 * st.x.fm / st.x.sm;
  if (st.y.df0 * st.y.sm < 2.0 * st.y.fm) st.y.df0 = 2.0 * st.y.fm / st.y.sm;
  st.x.fm *= friction;
  st.x.fs *= friction;
  st.y.fm *= friction;
  st.y.fs *= friction;
  // ax = fm_x / df0_x, ay = fm_y / df0_y; sx_hat = sm_x / (sm_x + sm_y) + ax / (ax + ay), and
  // sy_hat alike, with the four divisions folded into one.
  const double ax = st.x.fm * st.y.df0, ay = st.y.fm * st.x.df0;  // both times df0_x df0_y
  const double sm_sum = st.x.sm + st.y.sm, a_sum = ax + ay;
  const double inv = 1.0 / (sm_sum * a_sum);
  st.sx_hat = (st.x.sm * a_sum + ax * sm_sum) * inv;
  st.sy_hat = (st.y.sm * a_sum + ay * sm_sum) * inv;
  // The weighting grows with the load; beyond the load where rdyn is smallest it is held (as Chrono
  // and LFDM do), so rdyn never rises with the load again.
  const double l1 = p.rdyn_coefficient[0], l2 = p.rdyn_coefficient[1];
  const double q_min = l2 > l1 ? (1.0 - 2.0 * l1 + l2) / (2.0 * (l2 - l1)) : 1e300;
  const double lambda = tmeasy_slip_at_load(min_of(q, q_min), l1, l2);
  const double r_static = p.unloaded_radius - fz_c / p.vertical_stiffness;
  st.rdyn = lambda * p.unloaded_radius + (1.0 - lambda) * r_static;
  return st;
}

// Steady combined-slip forces: returns kx, ky with Fx = kx sx, Fy = ky sy (the generalised
// stiffnesses, finite at zero slip), scaled to the load fz (zero load: zero force).
struct TmeasyStiffness {
  double kx = 0, ky = 0;
};

TERRACAL_HD_INLINE TmeasyStiffness tmeasy_steady_stiffness(const TmeasyLoadState& st, double sx, double sy, double fz) {
  TmeasyStiffness k;
  if (fz <= 0.0) return k;
  const double inv_hxy = 1.0 / (st.sx_hat * st.sy_hat);
  const double inv_hx = st.sy_hat * inv_hxy, inv_hy = st.sx_hat * inv_hxy;
  const double sxn = sx * inv_hx, syn = sy * inv_hy;
  const double s = sqrt(sxn * sxn + syn * syn);
  double c = 0.7071067811865476, sn = 0.7071067811865476;  // direction of zero slip: any
  if (s > 1e-12) {
    const double inv_s = 1.0 / s;
    c = fabs(sxn) * inv_s;
    sn = fabs(syn) * inv_s;
  }
  // The combined curve's points along the slip direction; the sliding part only where reached.
  TmeasyCurve m;
  const double dx = st.x.df0 * st.sx_hat * c, dy = st.y.df0 * st.sy_hat * sn;
  m.df0 = sqrt(dx * dx + dy * dy);
  m.fm = sqrt(st.x.fm * c * st.x.fm * c + st.y.fm * sn * st.y.fm * sn);
  const double smx = st.x.sm * inv_hx * c, smy = st.y.sm * inv_hy * sn;
  m.sm = sqrt(smx * smx + smy * smy);
  double f_over_s;
  if (s <= m.sm) {
    const double sigma = s / m.sm;
    f_over_s = m.df0 / (1.0 + sigma * (sigma + m.df0 * m.sm / m.fm - 2.0));
  } else {
    m.fs = sqrt(st.x.fs * c * st.x.fs * c + st.y.fs * sn * st.y.fs * sn);
    const double ssx = st.x.ss * inv_hx * c, ssy = st.y.ss * inv_hy * sn;
    m.ss = sqrt(ssx * ssx + ssy * ssy);
    f_over_s = tmeasy_force_over_slip(m, s);
  }
  k.kx = f_over_s * inv_hx;
  k.ky = f_over_s * inv_hy;
  return k;
}

// Longitudinal and lateral slips from the contact point's velocity in the wheel frame (vx along the
// wheel's heading, vy to its left) and the spin omega.
struct TmeasySlips {
  double sx = 0, sy = 0, denominator = kTmeasySlipVelocity;
};
TERRACAL_HD_INLINE TmeasySlips tmeasy_slips(double vx, double vy, double omega, double rdyn) {
  TmeasySlips s;
  s.denominator = rdyn * fabs(omega) + kTmeasySlipVelocity;
  s.sx = -(vx - rdyn * omega) / s.denominator;
  s.sy = -vy / s.denominator;
  return s;
}

// The relaxation form (Rill): the tread deflects by (xe, ye) with stiffness c and damping d, and the
// deflection rate enters the slip: c xe + d dxe = k * -(vx + dxe - rdyn omega) / den. Solved for dxe,
// the denominator d * den + k is at least d * vN > 0, so standstill is safe.
struct TmeasyRelaxed {
  double fx = 0, fy = 0;    // forces on the wheel at the contact [N], wheel frame
  double dxe = 0, dye = 0;  // deflection rates [m/s]
};
TERRACAL_HD_INLINE TmeasyRelaxed tmeasy_relaxed(const TmeasyParams& p, const TmeasyStiffness& k, const TmeasySlips& s,
                                                double vx, double vy, double omega, double rdyn, double xe, double ye) {
  TmeasyRelaxed r;
  const double cx = p.longitudinal_stiffness, dx = p.longitudinal_damping;
  const double cy = p.lateral_stiffness, dy = p.lateral_damping;
  const double den_x = s.denominator * dx + k.kx, den_y = s.denominator * dy + k.ky;
  const double inv = 1.0 / (den_x * den_y);  // one division for both
  r.dxe = -(k.kx * (vx - rdyn * omega) + s.denominator * cx * xe) * den_y * inv;
  r.dye = -(k.ky * vy + s.denominator * cy * ye) * den_x * inv;
  r.fx = cx * xe + dx * r.dxe;
  r.fy = cy * ye + dy * r.dye;
  return r;
}

}  // namespace terracal
