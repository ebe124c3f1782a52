#pragma once
// CRM effect `artificial_viscosity`: Monaghan's artificial viscosity between approaching particles,
// -Pi_ij grad_i W_ij with Pi_ij = -alpha c_s mu_ij / rho_mean, mu_ij = h v_ij.r_ij / (r_ij^2 + 0.01 h^2).
// It damps the shocks of impacts and the ringing of elastic waves; it acts between soil particles
// and between soil and boundary markers, so bodies feel its reaction.
#include "highfi/crm/effects/crm_effect.hpp"

namespace terracal {

struct ArtificialViscosity : CrmEffect {
  static constexpr const char* kName = "artificial_viscosity";
  static constexpr bool kInLoop = true;
  static constexpr bool kInMarkerLoop = true;

  struct Settings {
    double alpha = 0.1;
  };
  static constexpr auto settings() {
    return std::array{real_setting("alpha", &Settings::alpha, Range{0, 2}, "Monaghan's alpha")};
  }

  template <class T>
  struct Constants {
    T alpha, sound_speed;
  };
  template <class T>
  static Constants<T> constants(const Settings& s, const CrmEffectInput& in) {
    return {T(s.alpha), T(in.soil.sound_speed())};
  }

  template <class T>
  TERRACAL_HD_INLINE static void pair_force(const SphConstants<T>& k, const Constants<T>& c, const Vec3<T>& vi, T rho_i,
                                            const Vec3<T>& vj, T rho_j, const Vec3<T>& rij, T r2, const Vec3<T>& grad,
                                            Vec3<T>& acc) {
    const T vr = dot(vi - vj, rij);
    if (vr < T(0)) {
      // Pi = -alpha c mu / rho_mean with mu = h vr / (r^2 + 0.01 h^2), in one division.
      const T h = k.kernel.h;
      const T pi = pair_div(T(-2) * c.alpha * c.sound_speed * h * vr, (r2 + T(0.01) * h * h) * (rho_i + rho_j));
      acc -= pi * grad;
    }
  }
};

}  // namespace terracal
