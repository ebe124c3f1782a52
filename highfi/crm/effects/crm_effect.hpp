#pragma once
// The shape of a CRM effect (docs/architecture.md, "Effects", has a worked example). An effect is a
// struct that derives from CrmEffect and, in one file, gives:
//   kName        its name in scenes ("effects": [...]) and its settings object's key;
//   Settings     its settings, each member's initialiser being its one default, and settings()
//                describing each one (key, range, help: core/setting.hpp);
//   Constants<T> what its terms need on the device, made by constants() from the settings and the
//                scene's soil and resolution (CrmEffectInput);
//   its terms    the hooks below that it overrides; the do-nothing defaults compile to nothing.
// The traits tell the core what the effect needs, so that an effect a scene does not name costs no
// memory, no pass and no instruction in the loops it would otherwise slow (core/effect_list.hpp).
// Adding an effect touches its own file, the registry (effects/crm_effects.hpp) and its test.
#include <array>

#include "core/setting.hpp"
#include "highfi/crm/crm_soil.hpp"
#include "highfi/crm/sph_pair.hpp"

namespace terracal {

// What an effect's constants() may read: the soil and the resolution of the scene.
struct CrmEffectInput {
  const CrmSoil& soil;
  double h;        // smoothing length [m]
  double spacing;  // d0 [m]
};

struct CrmEffect {
  // --- Traits ---------------------------------------------------------------------------------
  // Terms in the soil pass (pair_soil, listed, finish): the pass is compiled with or without it.
  static constexpr bool kInLoop = false;
  // Terms in the marker pass (pair_force also applies there; marker_pair, marker_finish).
  static constexpr bool kInMarkerLoop = false;
  // Keeps a Vec4 per particle (sorted with the particles, carried by frozen ones, checkpointed as
  // "soil_<kRecordName>"; zero in a bed settled without the effect).
  static constexpr bool kRecord = false;
  static constexpr const char* kRecordName = "";
  // Reads SoilSums::drift, the kernel-weighted relative velocity of the neighbours.
  static constexpr bool kUsesDrift = false;
  // Has pair terms with sums of its own (listed): the CPU adds them in a scalar pass over the
  // listed neighbours, the GPU inside its neighbour loop.
  static constexpr bool kListed = false;
  // Acts only around moving bodies: a bed settled without bodies is the same with or without it,
  // so the settled-bed cache's key leaves it out.
  static constexpr bool kOnlyAroundBodies = false;

  // --- Host -----------------------------------------------------------------------------------
  template <class T>
  struct Constants {};
  template <class T, class S>
  static Constants<T> constants(const S&, const CrmEffectInput&) {
    return {};
  }
  // Changes the soil model's constants (cohesion).
  template <class S, class M>
  static void soil_model(const S&, const CrmSoil&, M&) {}
  // Scene-level rules, also for an effect that is not named; fail(key, what) refuses the scene.
  template <class Scene, class Fail>
  static void check_scene(const Scene&, bool /*named*/, Fail&&) {}
  // Before each step, with the solver's bodies and engine (active_domain).
  template <class S, class Step>
  static void before_step(const S&, Step&) {}

  // --- Device: the terms (T is the precision of the particle state) ----------------------------
  // Sums of its own over a particle's neighbours (kListed), and over a marker's soil neighbours.
  template <class T>
  struct Sums {
    TERRACAL_HD Sums& operator+=(const Sums&) { return *this; }
  };
  template <class T>
  struct MarkerSums {};
  // A force term of every pair, soil-soil and soil-marker, added to the pair's acceleration acc
  // (per unit neighbour mass); the marker pass applies it too, so bodies feel its reaction.
  template <class T, class C>
  TERRACAL_HD_INLINE static void pair_force(const SphConstants<T>&, const C&, const Vec3<T>& /*vi*/, T /*rho_i*/,
                                            const Vec3<T>& /*vj*/, T /*rho_j*/, const Vec3<T>& /*rij*/, T /*r2*/,
                                            const Vec3<T>& /*grad*/, Vec3<T>& /*acc*/) {}
  // A term of a pair of soil particles only, added to the neighbour's share c.
  template <class T, class C>
  TERRACAL_HD_INLINE static void pair_soil(const SphConstants<T>&, const C&, const SoilSelf<T>&, const Neighbour<T>&,
                                           SoilSums<T>&) {}
  // The effect's own sums (kListed): neighbour j at pj with velocity vj, its share vw = V_j W_ij of
  // the support and its record (zero for a marker).
  template <class T, class C, class Own>
  TERRACAL_HD_INLINE static void listed(const SphConstants<T>&, const C&, const Vec3<T>& /*xi*/, const Vec4<T>& /*pj*/,
                                        const Vec4<T>& /*vj*/, T /*vw*/, const Vec4<T>& /*record_j*/, Own&) {}
  // Per particle, after the sums: adds to the update's acceleration and drift, and writes the new
  // record from the one the stage started from (base) and the one it is evaluated at (eval).
  template <class T, class C, class Own>
  TERRACAL_HD_INLINE static void finish(const SphConstants<T>&, const C&, const Own&, const ParticleUpdate<T>&,
                                        const Vec4<T>& /*record_eval*/, const Vec4<T>& /*record_base*/,
                                        Vec3<T>& /*acc*/, Vec3<T>& /*drift*/, Vec4<T>& /*record_out*/) {}
  // The marker pass: a soil neighbour j of a marker (kernel value w, its record) ...
  template <class T, class C, class Own>
  TERRACAL_HD_INLINE static void marker_pair(const SphConstants<T>&, const C&, T /*w*/, const Vec4<T>& /*record_j*/,
                                             Own&) {}
  // ... and the marker's total: adds to f, the force of the soil on the marker per unit mass squared.
  template <class T, class C, class Own>
  TERRACAL_HD_INLINE static void marker_finish(const SphConstants<T>&, const C&, T /*rho_m*/, const Own&,
                                               Vec3<T>& /*f*/) {}
};

}  // namespace terracal
