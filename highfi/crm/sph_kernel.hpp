#pragma once
// SPH smoothing kernels with support radius 2h (docs/architecture.md, "CRM"). The gradient is
// returned as a factor F with grad_i W_ij = F * (x_i - x_j), which avoids a division by r in the hot
// loop.
#include "core/host_device.hpp"

namespace terracal {

enum class KernelType : int { kWendlandC2 = 0, kCubicSpline = 1 };

template <typename T>
struct SphKernel {
  KernelType type = KernelType::kWendlandC2;
  T h = 1, inv_h = 1, alpha = 1;  // alpha: normalisation 21/(16 pi h^3) or 1/(pi h^3)

  static SphKernel make(KernelType type, double h) {
    constexpr double kPi = 3.14159265358979323846;
    SphKernel k;
    k.type = type;
    k.h = T(h);
    k.inv_h = T(1.0 / h);
    k.alpha = T(type == KernelType::kWendlandC2 ? 21.0 / (16.0 * kPi * h * h * h) : 1.0 / (kPi * h * h * h));
    return k;
  }
  TERRACAL_HD T support2() const { return T(4) * h * h; }

  TERRACAL_HD T w(T r) const {
    const T q = r * inv_h;
    if (q >= T(2)) return T(0);
    if (type == KernelType::kWendlandC2) {
      const T a = T(1) - T(0.5) * q;
      const T a2 = a * a;
      return alpha * a2 * a2 * (T(2) * q + T(1));
    }
    if (q < T(1)) return alpha * (T(1) - T(1.5) * q * q + T(0.75) * q * q * q);
    const T b = T(2) - q;
    return alpha * T(0.25) * b * b * b;
  }

  // W(r) and F(r) together, for the hot loop: they share (1 - q/2)^3 (or (2 - q)^2).
  struct Values {
    T w, f;
  };
  TERRACAL_HD Values values(T r) const {
    const T q = r * inv_h;
    if (q >= T(2)) return {T(0), T(0)};
    const T c = alpha * inv_h * inv_h;
    if (type == KernelType::kWendlandC2) {
      const T a = T(1) - T(0.5) * q;
      const T a3 = a * a * a;
      return {alpha * a3 * a * (T(2) * q + T(1)), T(-5) * c * a3};
    }
    if (q < T(1)) return {alpha * (T(1) - T(1.5) * q * q + T(0.75) * q * q * q), c * (T(-3) + T(2.25) * q)};
    const T b = T(2) - q;
    return {alpha * T(0.25) * b * b * b, T(-0.75) * c * b * b / q};
  }

  // F(r) such that grad_i W(|x_i - x_j|) = F * (x_i - x_j).
  TERRACAL_HD T grad_factor(T r) const {
    const T q = r * inv_h;
    if (q >= T(2)) return T(0);
    const T c = alpha * inv_h * inv_h;
    if (type == KernelType::kWendlandC2) {
      const T a = T(1) - T(0.5) * q;
      return T(-5) * c * a * a * a;  // dW/dr = -5 alpha q (1-q/2)^3 / h, divided by r = q h
    }
    if (q < T(1)) return c * (T(-3) + T(2.25) * q);
    const T b = T(2) - q;
    return T(-0.75) * c * b * b / q;
  }
};

}  // namespace terracal
