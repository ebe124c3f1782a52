#pragma once
// CRM effect `hourglass_damping`: Morris' SPH Laplacian nu lap(v) on the whole relative velocity of
// two soil particles, with nu = alpha h c_s / 10 (the shear viscosity that Monaghan's term carries in
// 3D for the same alpha). It vanishes on any linear velocity field (interior, symmetric
// neighbourhood), so uniform strain rates and rigid rotation go undamped, but it damps the
// lattice's checkerboard modes, in which neighbours move past each other and which neither the
// velocity gradient nor the artificial viscosity (along r_ij only) sees. Symmetric in i and j:
// momentum is conserved. Boundary markers take no part in it. Why the rigs use alpha 0.4:
// docs/decisions.md.
#include "highfi/crm/effects/crm_effect.hpp"

namespace terracal {

struct HourglassDamping : CrmEffect {
  static constexpr const char* kName = "hourglass_damping";
  static constexpr bool kInLoop = true;

  struct Settings {
    double alpha = 0.4;
  };
  static constexpr auto settings() {
    return std::array{
        real_setting("alpha", &Settings::alpha, Range{0, 2, true, false}, "Laplacian viscosity nu = alpha h c_s / 10")};
  }

  template <class T>
  struct Constants {
    T nu;  // kinematic viscosity [m^2/s]
  };
  template <class T>
  static Constants<T> constants(const Settings& s, const CrmEffectInput& in) {
    return {T(s.alpha * in.h * in.soil.sound_speed() / 10)};
  }

  template <class T>
  TERRACAL_HD_INLINE static void pair_soil(const SphConstants<T>& k, const Constants<T>& c, const SoilSelf<T>& me,
                                           const Neighbour<T>& nb, SoilSums<T>& share) {
    const T h = k.kernel.h;
    const T lap = pair_div(c.nu * (me.inv_rho + nb.inv_rho) * nb.kv.f * nb.r2, nb.r2 + T(0.01) * h * h);
    share.acc -= lap * nb.dv;
  }
};

}  // namespace terracal
