#pragma once
// Analytic bevameter forward models. Templated on the scalar so that Ceres
// differentiates them automatically (Jets) and marked host/device so that GPU batch evaluators
// use the very same source.
#include <cmath>

#include "core/host_device.hpp"

namespace terracal::bayes {

inline constexpr double kPi = 3.14159265358979323846;

// Bekker-Wong plate force for a circular plate of radius r (Bekker width b = r) at sinkage z:
// F = pi r^2 (Kc/r + Kphi) z^n. Written as two factors, the plate's stiffness and z^n, because
// a data set repeats the same sinkages for every plate: the likelihood computes each z^n once.
template <typename T>
TERRACAL_HD T plate_stiffness(double r, const T& Kc, const T& Kphi) {
  return kPi * r * r * (Kc / r + Kphi);
}
template <typename T>
TERRACAL_HD T sinkage_power(double log_z, const T& n) {
  using std::exp;
  return exp(n * log_z);
}
template <typename T>
TERRACAL_HD T plate_force_log(double r, double log_z, const T& Kc, const T& Kphi, const T& n) {
  return plate_stiffness(r, Kc, Kphi) * sinkage_power(log_z, n);
}
template <typename T>
TERRACAL_HD T plate_force(double r, double z, const T& Kc, const T& Kphi, const T& n) {
  if (!(z > 0.0)) return T(0.0);  // no sinkage, no force (and no log(0) in the derivative)
  return plate_force_log(r, std::log(z), Kc, Kphi, n);
}

// H(x) = (1/x^3) * integral_0^x t^2 (1 - e^{-t}) dt, the dimensionless shear-development
// integral of the annulus: integral_0^R r^2 (1 - e^{-a r}) dr = R^3 H(a R). H(0) = 0, H(inf) = 1/3.
// The closed form cancels for small x (it loses about one digit at x = 1), so an alternating
// series serves below 1, stopped once a term no longer changes the sum.
template <typename T>
TERRACAL_HD T shear_development(const T& x) {
  using std::abs;
  using std::exp;
  if (x < 1.0) {
    // H(x) = sum_{k>=1} (-1)^{k+1} x^k / (k! (k+3)); at x < 1 at most 18 terms reach 1e-16.
    T term = x;  // x^k / k!
    T sum = term / 4.0;
    for (int k = 2; k <= 20; ++k) {
      term = term * x / double(k);
      const T add = term / double(k + 3);
      sum += (k % 2 == 0 ? -1.0 : 1.0) * add;
      if (abs(add) < 1e-17 * abs(sum)) break;
    }
    return sum;
  }
  // H(x) = 1/3 - (2 - e^{-x}(x^2 + 2x + 2)) / x^3
  return 1.0 / 3.0 - (2.0 - exp(-x) * (x * x + 2.0 * x + 2.0)) / (x * x * x);
}

// Annulus shear torque: the exact integral over the annulus (r_in..r_out) of
// tau(r) r dA with tau = tau_max (1 - e^{-r theta / k}), tau_max = c + p tan phi, p = W / A,
// dA = 2 pi r dr. Factored as tau_max (soil strength under the load) times the development
// 2 pi integral r^2 (1 - e^{-r theta/k}) dr (geometry and displacement), since a data set repeats
// the same angles for every load. phi in degrees (Chrono's unit).
template <typename T>
TERRACAL_HD T annulus_shear_strength(double r_in, double r_out, double normal_load, const T& c, const T& tan_phi) {
  const double area = kPi * (r_out * r_out - r_in * r_in);
  return c + (normal_load / area) * tan_phi;
}
template <typename T>
TERRACAL_HD T tan_degrees(const T& phi_deg) {
  using std::tan;
  return tan(phi_deg * (kPi / 180.0));
}
template <typename T>
TERRACAL_HD T annulus_development(double r_in, double r_out, double theta, const T& k) {
  const T a = theta / k;  // 1/m
  return 2.0 * kPi *
         (r_out * r_out * r_out * shear_development(a * r_out) - r_in * r_in * r_in * shear_development(a * r_in));
}
// The fully developed limit (theta -> infinity): 2 pi (r_out^3 - r_in^3) / 3.
inline TERRACAL_HD double annulus_development_full(double r_in, double r_out) {
  return 2.0 * kPi * (r_out * r_out * r_out - r_in * r_in * r_in) / 3.0;
}

template <typename T>
TERRACAL_HD T annulus_torque(double r_in, double r_out, double normal_load, double theta, const T& c, const T& phi_deg,
                             const T& k) {
  return annulus_shear_strength(r_in, r_out, normal_load, c, tan_degrees(phi_deg)) *
         annulus_development(r_in, r_out, theta, k);
}
template <typename T>
TERRACAL_HD T annulus_torque_developed(double r_in, double r_out, double normal_load, const T& c, const T& phi_deg) {
  return annulus_shear_strength(r_in, r_out, normal_load, c, tan_degrees(phi_deg)) *
         annulus_development_full(r_in, r_out);
}

}  // namespace terracal::bayes
