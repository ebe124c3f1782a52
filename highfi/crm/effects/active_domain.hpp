#pragma once
// CRM effect `active_domain`: only the soil within a box around each moving body (its bounding
// radius plus a margin) is integrated; the rest is frozen at rest, left out of the sums of the
// stage's arithmetic (on the GPU, out of the stages' launches: they run over a list of the active
// particles). With a sort skin the boxes follow the bodies in steps of at most the drift
// (docs/decisions.md, "Sort skin"). Wall markers beyond the kernel's support (and that drift) of
// every box are skipped too (only frozen soil sees them), so the walls' wrench counts only the
// markers near the boxes. It pays where the bodies stir a small part of a large bed (a wheel
// crossing a long bin: bench/RESULTS.md); the bodies' forces stay within 1 % of the full domain's
// at the default margin (tests/highfi/crm/test_crm_active_domain.cpp).
#include <vector>

#include "highfi/crm/effects/crm_effect.hpp"

namespace terracal {

struct ActiveDomain : CrmEffect {
  static constexpr const char* kName = "active_domain";
  static constexpr bool kOnlyAroundBodies = true;

  struct Settings {
    double margin = 0.1;
  };
  static constexpr auto settings() {
    return std::array{real_setting("margin", &Settings::margin, Range{0, 100, true, false, "m"},
                                   "soil within this distance of a moving body's bounding sphere is integrated")};
  }

  // Step: the solver's view of a step (CrmStepView, crm_solver.hpp): the scene's bodies, their
  // states and the engine. No moving body: nothing to focus on, so every particle is integrated.
  template <class Step>
  static void before_step(const Settings& s, Step& step) {
    std::vector<ActiveBox<double>> boxes;
    for (std::size_t b = 0; b < step.states.size(); ++b) {
      if (!step.bodies[b].motion.moves()) continue;
      const double r = step.bodies[b].bounding_radius() + s.margin;
      const Vec3<double> c = step.states[b].position;
      boxes.push_back({c - Vec3<double>{r, r, r}, c + Vec3<double>{r, r, r}});
    }
    step.engine.set_active(boxes);
  }
};

}  // namespace terracal
