#pragma once
// SCM effect `damping`: a normal pressure R v_n against the speed at which a body sinks into the soil
// (Chrono's SCM "Damping", R from the soil's parameters). It drains the energy of a body bouncing on
// the elastic soil; without it, stiff soils whose elastic bed nothing else damps can keep a wheel
// hopping (results/scm_vs_wong_reece/hop.md).
#include <algorithm>

#include "lowfi/effects/scm_effect.hpp"

namespace terracal::lowfi {

struct ScmDamping : ScmEffect {
  static constexpr const char* kName = "damping";
  struct Settings {};
  static constexpr auto settings() { return no_settings<Settings>(); }

  static void pressure(const Settings&, const ScmSoil& soil, const Vec3<double>& v, const Vec3<double>& nrm,
                       double& sigma) {
    sigma += soil.damping * std::max(0.0, -dot(v, nrm));
  }
};

}  // namespace terracal::lowfi
