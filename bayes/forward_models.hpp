#pragma once
// Analytic bevameter forward models (issue 2, point 4). Templated on the scalar so that Ceres
// differentiates them automatically (Jets) and marked host/device so that GPU batch evaluators
// use the very same source.
#include <cmath>

#include "core/host_device.hpp"

namespace terracal::bayes {

inline constexpr double kPi = 3.14159265358979323846;

// Bekker-Wong plate force for a circular plate of radius r (Bekker width b = r) at sinkage z:
// F = pi r^2 (Kc/r + Kphi) z^n. The likelihood calls the log_z form with log z precomputed
// (one exp per point instead of a pow); both are the same formula.
template <typename T>
TERRACAL_HD T plate_force_log(double r, double log_z, const T& Kc, const T& Kphi, const T& n) {
  using std::exp;
  return kPi * r * r * (Kc / r + Kphi) * exp(n * log_z);
}
template <typename T>
TERRACAL_HD T plate_force(double r, double z, const T& Kc, const T& Kphi, const T& n) {
  if (!(z > 0.0)) return T(0.0);  // no sinkage, no force (and no log(0) in the derivative)
  return plate_force_log(r, std::log(z), Kc, Kphi, n);
}

// H(x) = (1/x^3) * integral_0^x t^2 (1 - e^{-t}) dt, the dimensionless shear-development
// integral of the annulus: integral_0^R r^2 (1 - e^{-a r}) dr = R^3 H(a R). H(0) = 0, H(inf) = 1/3.
// The closed form cancels catastrophically for small x, so an alternating series serves there.
template <typename T>
TERRACAL_HD T shear_development(const T& x) {
  using std::exp;
  if (x < 2.0) {
    // H(x) = sum_{k>=1} (-1)^{k+1} x^k / (k! (k+3)); at x < 2 twenty-five terms reach 1e-16.
    T term = x;   // x^k / k!
    T sum = term / 4.0;
    for (int k = 2; k <= 25; ++k) {
      term = term * x / double(k);
      sum += (k % 2 == 0 ? -1.0 : 1.0) * term / double(k + 3);
    }
    return sum;
  }
  // H(x) = 1/3 - (2 - e^{-x}(x^2 + 2x + 2)) / x^3
  return 1.0 / 3.0 - (2.0 - exp(-x) * (x * x + 2.0 * x + 2.0)) / (x * x * x);
}

// Annulus shear torque: the exact integral over the annulus (r_in..r_out) of
// tau(r) r dA with tau = (c + p tan phi)(1 - e^{-r theta / k}), p = W / A, dA = 2 pi r dr.
// phi in degrees (Chrono's unit). theta < 0 is not physical and is rejected by the data loader.
template <typename T>
TERRACAL_HD T annulus_torque(double r_in, double r_out, double normal_load, double theta,
                             const T& c, const T& phi_deg, const T& k) {
  using std::tan;
  const double area = kPi * (r_out * r_out - r_in * r_in);
  const T tau_max = c + (normal_load / area) * tan(phi_deg * (kPi / 180.0));
  const T a = theta / k;  // 1/m
  const T integral = r_out * r_out * r_out * shear_development(a * r_out) -
                     r_in * r_in * r_in * shear_development(a * r_in);
  return 2.0 * kPi * tau_max * integral;
}

// The fully developed torque (theta -> infinity): 2 pi tau_max (r_out^3 - r_in^3) / 3.
template <typename T>
TERRACAL_HD T annulus_torque_developed(double r_in, double r_out, double normal_load, const T& c, const T& phi_deg) {
  using std::tan;
  const double area = kPi * (r_out * r_out - r_in * r_in);
  const T tau_max = c + (normal_load / area) * tan(phi_deg * (kPi / 180.0));
  return 2.0 * kPi * tau_max * (r_out * r_out * r_out - r_in * r_in * r_in) / 3.0;
}

}  // namespace terracal::bayes
