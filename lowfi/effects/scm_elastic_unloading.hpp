#pragma once
// SCM effect `elastic_unloading`: when a body leaves a node, the soil springs back by the elastic part
// it still holds (sigma/Ke), even if the body left at once. In force terms this is Chrono's SCM, whose
// stress counts from the plastic sinkage whatever level it draws.
// Without it, the rut stays where the body last held it (Chrono's drawn level) and so does the
// soil's spring: a body rising slowly has had the soil follow it up elastically, so its rut has sprung
// back; one that leaves at once leaves the soil compressed, and that elastic part becomes permanent.
// Keeping the deepest sinkage instead would let the soil push a rising body up and then not be there
// to stop it coming down: energy from nowhere, which made a slow wheel on stiff soil hop
// (results/scm_vs_wong_reece/hop.md).
#include "lowfi/effects/scm_effect.hpp"

namespace terracal::lowfi {

struct ScmElasticUnloading : ScmEffect {
  static constexpr const char* kName = "elastic_unloading";
  struct Settings {};
  static constexpr auto settings() { return no_settings<Settings>(); }

  static void release(const Settings&, const ScmNode& n, double& rut) { rut = n.plastic_sinkage; }
};

}  // namespace terracal::lowfi
