#pragma once
// The soil's constitutive law, shared by both backends: Jaumann stress rate with isotropic
// elasticity, and mu(I) plasticity by radial return (docs/architecture.md, "CRM"). Drucker-Prager
// is mu_2 = mu_s.
#include <cmath>

#include "core/host_device.hpp"
#include "core/vec.hpp"

namespace terracal {

template <typename T>
struct SoilModel {
  T shear_modulus = 0, bulk_modulus = 0;  // G = E/(2(1+nu)), K = E/(3(1-2nu))
  T mu_s = 0, mu_2 = 0, I0 = 0, grain_diameter = 0, rho0 = 0;
  T cohesion = 0;  // zero unless the scene names the `cohesion` effect
};

// d sigma / dt = W sigma - sigma W + 2G dev(D) + K tr(D) I, with L = grad v, D = sym L, W = skew L.
template <typename T>
TERRACAL_HD inline Sym3<T> jaumann_rate(const Sym3<T>& s, const Mat3<T>& L, const SoilModel<T>& m) {
  const T dxx = L.m[0][0], dyy = L.m[1][1], dzz = L.m[2][2];
  const T dxy = T(0.5) * (L.m[0][1] + L.m[1][0]), dxz = T(0.5) * (L.m[0][2] + L.m[2][0]),
          dyz = T(0.5) * (L.m[1][2] + L.m[2][1]);
  const T wxy = T(0.5) * (L.m[0][1] - L.m[1][0]), wxz = T(0.5) * (L.m[0][2] - L.m[2][0]),
          wyz = T(0.5) * (L.m[1][2] - L.m[2][1]);
  // M = W sigma with W = [[0, wxy, wxz], [-wxy, 0, wyz], [-wxz, -wyz, 0]]; the rotation term is M + M^T.
  const T m00 = wxy * s.xy + wxz * s.xz, m01 = wxy * s.yy + wxz * s.yz, m02 = wxy * s.yz + wxz * s.zz;
  const T m10 = -wxy * s.xx + wyz * s.xz, m11 = -wxy * s.xy + wyz * s.yz, m12 = -wxy * s.xz + wyz * s.zz;
  const T m20 = -wxz * s.xx - wyz * s.xy, m21 = -wxz * s.xy - wyz * s.yy, m22 = -wxz * s.xz - wyz * s.yz;
  const T trd = dxx + dyy + dzz;
  const T g2 = T(2) * m.shear_modulus, lam = m.bulk_modulus * trd - g2 * trd / T(3);
  Sym3<T> r;
  r.xx = T(2) * m00 + g2 * dxx + lam;
  r.yy = T(2) * m11 + g2 * dyy + lam;
  r.zz = T(2) * m22 + g2 * dzz + lam;
  r.xy = m01 + m10 + g2 * dxy;
  r.xz = m02 + m20 + g2 * dxz;
  r.yz = m12 + m21 + g2 * dyz;
  return r;
}

// Shear rate gamma_dot = sqrt(2 D':D') (equals the engineering shear rate in simple shear).
template <typename T>
TERRACAL_HD inline T shear_rate(const Mat3<T>& L) {
  const T dxx = L.m[0][0], dyy = L.m[1][1], dzz = L.m[2][2];
  const T t = (dxx + dyy + dzz) / T(3);
  const T dxy = T(0.5) * (L.m[0][1] + L.m[1][0]), dxz = T(0.5) * (L.m[0][2] + L.m[2][0]),
          dyz = T(0.5) * (L.m[1][2] + L.m[2][1]);
  const T dd = (dxx - t) * (dxx - t) + (dyy - t) * (dyy - t) + (dzz - t) * (dzz - t) +
               T(2) * (dxy * dxy + dxz * dxz + dyz * dyz);
  return std::sqrt(T(2) * dd);
}

// Radial return onto the mu(I) cone: p = -tr(sigma)/3 clamped at >= 0 (no tension),
// tau = sqrt(s:s/2), tau_max = mu(I) p + c; if tau > tau_max the deviator is scaled back.
// Returns the plastic shear increment (tau - tau_max)/G, zero when the step stays elastic.
template <typename T>
TERRACAL_HD inline T return_map(Sym3<T>& s, T gamma_dot, const SoilModel<T>& m) {
  T p = -s.trace() / T(3);
  if (!(p > T(0))) p = T(0);  // also maps NaN to the apex: no tension, and no propagation of bad values
  Sym3<T> dev{s.xx + p, s.yy + p, s.zz + p, s.xy, s.xz, s.yz};
  const T tau = std::sqrt(T(0.5) * double_dot(dev));
  T mu = m.mu_s;
  if (m.mu_2 != m.mu_s) {
    // I = d gamma_dot sqrt(rho0 / p); written as I/(I0 + I) = d g / (I0 sqrt(p/rho0) + d g) so p -> 0 is safe.
    const T dg = m.grain_diameter * gamma_dot;
    const T denom = m.I0 * std::sqrt(p / m.rho0) + dg;
    if (denom > T(0)) mu += (m.mu_2 - m.mu_s) * dg / denom;
  }
  const T tau_max = mu * p + m.cohesion;
  T plastic = T(0);
  if (tau > tau_max) {
    const T f = tau > T(0) ? tau_max / tau : T(0);
    dev = f * dev;
    plastic = (tau - tau_max) / m.shear_modulus;
  }
  s = Sym3<T>{dev.xx - p, dev.yy - p, dev.zz - p, dev.xy, dev.xz, dev.yz};
  return plastic;
}

// The highest density a particle may carry: 1.5 rho0, or 1.2 times what its pressure implies where
// that is higher. Density and pressure integrate the same velocity divergence (d rho / rho = dp / K;
// plastic flow keeps the volume), so rho = rho0 exp(p / K) for soil that starts at rest. Where that
// tie is lost (a stress-free particle squeezed against a wall) the divergence would grow the density
// without bound; the fixed 1.5 rho0 stops it. Soil under very high pressure (p/K > ln 1.25 = 0.22, a
// plate driven towards the floor) must be allowed past 1.5 rho0 or it blows up, so there the cap
// follows the pressure. At ordinary pressures the bound stays the fixed one: particles against a
// rolling wheel's rim drift up to it, the wheel bears on them, and a cap loosened with the pressure
// there (1.5 rho0 exp(p/K)) let the wheel keep sinking (docs/decisions.md, "Density cap").
template <typename T>
TERRACAL_HD inline T density_cap(T pressure, const SoilModel<T>& m) {
  const T tied = T(1.2) * m.rho0 * std::exp((pressure > T(0) ? pressure : T(0)) / m.bulk_modulus);
  const T fixed = T(1.5) * m.rho0;
  return tied > fixed ? tied : fixed;
}

// Whether a particle's density is held at density_cap (within 0.1 %), from its stress's first three
// components (xx, yy, zz): where many are, the cap rather than the soil sets the result.
template <typename T>
TERRACAL_HD inline bool at_density_cap(T rho, const Vec4<T>& s0, const SoilModel<T>& m) {
  return rho >= T(0.999) * density_cap(-(s0.x + s0.y + s0.z) / T(3), m);
}

}  // namespace terracal
