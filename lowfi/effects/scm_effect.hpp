#pragma once
// The shape of an SCM effect (docs/architecture.md, "Effects"): a struct that derives from ScmEffect
// and, in one file, gives its name (kName), its settings (each member's initialiser its one default,
// described by settings(): core/setting.hpp) and the hooks below that it overrides. The terrain
// calls the hooks of the named effects in registry order (effects/scm_effects.hpp); an effect that
// is not named costs one test of a bit per node and step. Adding an effect touches its own file, the
// registry and its test.
#include <array>
#include <vector>

#include "core/setting.hpp"
#include "lowfi/contact_patches.hpp"
#include "lowfi/scm_nodes.hpp"
#include "lowfi/scm_soil.hpp"

namespace terracal::lowfi {

// What the terrain hands an effect after a step's contact: the pressed nodes (in the order of the
// patches' numbering), their patches, the plastic volume each patch pushed down this step, the grid.
struct ScmContactView {
  const std::vector<GridIndex>& pressed;
  const ContactPatches& patches;
  const std::vector<double>& displaced;  // per patch [m^3]
  ScmNodeGrid& nodes;
  double grid;  // node spacing [m]
};

struct ScmEffect {
  // The yield pressure p of a pressed node at sinkage z under a contact of width b (the core's:
  // Bekker's law), from the body's velocity v at the node, its translational velocity u and the
  // outward normal n of its underside.
  template <class S>
  static void yield(const S&, const ScmSoil&, const Vec3<double>& /*v*/, const Vec3<double>& /*u*/,
                    const Vec3<double>& /*n*/, double /*z*/, double /*b*/, double& /*p*/) {}
  // A term of the normal pressure sigma at a pressed node, from the body's velocity v there and the
  // outward normal n of its underside.
  template <class S>
  static void pressure(const S&, const ScmSoil&, const Vec3<double>& /*v*/, const Vec3<double>& /*n*/,
                       double& /*sigma*/) {}
  // A node the bodies left this step: `rut` is the plastic sinkage it keeps (the core's rule: where
  // the body last held it).
  template <class S>
  static void release(const S&, const ScmNode&, double& /*rut*/) {}
  // After the step's contact: changes to the surface (bulldozing).
  template <class S>
  static void after_contact(const S&, ScmContactView&) {}
};

}  // namespace terracal::lowfi
