#pragma once
// CRM effect `cohesion`: the soil's cohesion c (the material's "cohesion", Pa) in the yield stress of
// the mu(I) return map, tau_max = mu p + c (soil_model.hpp), and in the hold of hourglass_stiffness's
// frictional spring. Its term is a constant of the constitutive law, zero when the effect is off:
// one addition per particle and stage, so the loop is the same with and without it. A soil with
// cohesion must name the effect, so that no cohesion acts unless the scene says so.
#include "highfi/crm/effects/crm_effect.hpp"

#include <fmt/format.h>

namespace terracal {

struct Cohesion : CrmEffect {
  static constexpr const char* kName = "cohesion";

  struct Settings {};
  static constexpr auto settings() { return no_settings<Settings>(); }

  template <class M>
  static void soil_model(const Settings&, const CrmSoil& soil, M& model) {
    model.cohesion = soil.cohesion;
  }
  template <class Scene, class Fail>
  static void check_scene(const Scene& scene, bool named, Fail&& fail) {
    if (scene.soil.cohesion > 0 && !named)
      fail("soil.cohesion", fmt::format("value {} Pa needs the effect \"cohesion\" in 'effects'", scene.soil.cohesion));
  }
};

}  // namespace terracal
