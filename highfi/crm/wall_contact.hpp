#pragma once
// The walls' contact pressure (resolution.wall_contact), written once for both backends. Boundary
// markers push soil back only through the stress extrapolated onto them (Adami et al. 2012), so a
// wall holds soil only as well as the kernel's gradient lets it. Where soil is strongly compressed
// against a wall (p/K of order one, in a closed box) the particles in contact close in on the
// markers as the pressure grows; past the distance where |grad W| peaks (0.7 spacings at h/d0 1.4)
// a marker pushes them back less the nearer they come, and they are pushed through the wall. With
// the contact pressure a particle closer to a marker than a spacing d0 also meets
//   p_c = wall_contact p (1 - r / d0)   (p > 0 the particle's own pressure),
// added to the marker's stress for that pair, in the soil's pass and in the marker's (so that bodies
// feel its reaction). It scales with the soil's pressure, like the push that drives the particle in;
// its reach is a spacing because a particle slipping between four markers crosses the wall's surface
// 0.87 spacings from them. It is off by default: it also acts on soil in ordinary contact pressed a
// little closer than a spacing, and changes a held footing's force by a few per cent
// (docs/decisions.md, "Wall contact").
#include <cmath>

#include "highfi/crm/sph_fields.hpp"

namespace terracal {

// The contact pressure of a marker at distance r from a soil particle of pressure p, or of stress s
// (branch-free: it runs in the CPU's SIMD loop); 0 when off (wall_contact = 0).
template <typename T>
TERRACAL_HD inline T wall_contact_pressure_at(const SphConstants<T>& k, T r, T p) {
  const T overlap = T(1) - r * k.wall_contact_inv_reach;
  return overlap > T(0) && p > T(0) ? k.wall_contact * p * overlap : T(0);
}
template <typename T>
TERRACAL_HD inline T wall_contact_pressure(const SphConstants<T>& k, T r, const Sym3<T>& s) {
  return wall_contact_pressure_at(k, r, -s.trace() / T(3));
}

// s - p I: a stress with the pressure p added.
template <typename T>
TERRACAL_HD inline Sym3<T> plus_pressure(Sym3<T> s, T p) {
  s.xx -= p;
  s.yy -= p;
  s.zz -= p;
  return s;
}

}  // namespace terracal
