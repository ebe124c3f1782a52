#pragma once
// CRM effect `shifting`: XSPH, which moves each particle with its velocity plus epsilon times the
// kernel-weighted mean velocity of its neighbours relative to it, sum_j V_j W_ij (v_j - v_i). It
// keeps the particle distribution even where the flow would cluster particles; the velocity that
// enters the momentum balance is unchanged.
#include "highfi/crm/effects/crm_effect.hpp"

namespace terracal {

struct Shifting : CrmEffect {
  static constexpr const char* kName = "shifting";
  static constexpr bool kInLoop = true;
  static constexpr bool kUsesDrift = true;

  struct Settings {
    double xsph = 0.5;
  };
  static constexpr auto settings() {
    return std::array{real_setting("xsph", &Settings::xsph, Range{0, 1}, "XSPH epsilon")};
  }

  template <class T>
  struct Constants {
    T xsph;
  };
  template <class T>
  static Constants<T> constants(const Settings& s, const CrmEffectInput&) {
    return {T(s.xsph)};
  }

  template <class T, class Own>
  TERRACAL_HD_INLINE static void finish(const SphConstants<T>&, const Constants<T>& c, const Own&,
                                        const ParticleUpdate<T>& u, const Vec4<T>&, const Vec4<T>&, Vec3<T>&,
                                        Vec3<T>& drift, Vec4<T>&) {
    drift += c.xsph * u.sum.drift;
  }
};

}  // namespace terracal
