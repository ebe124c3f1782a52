#pragma once
// The arithmetic of one pair of particles, written once for both backends (docs/architecture.md,
// "CRM"): the core sums of a soil particle over its neighbours, and the places where the named
// effects (highfi/crm/effects/) add their pair terms. Fx is the compile-time list of the effects a
// scene names (core/effect_list.hpp); the core calls each effect's hooks in registry order.
#include <cmath>

#include "core/effect_list.hpp"
#include "core/pair_math.hpp"
#include "highfi/crm/sph_fields.hpp"
#include "highfi/crm/wall_contact.hpp"

namespace terracal {

// A soil particle's own state, as the sums over its neighbours need it: its stress enters them only
// as sigma / rho^2 (the pair term) and as its pressure (the walls' contact), so those are what it
// keeps, worked out once per particle rather than once per pair.
template <typename T>
struct SoilSelf {
  Vec3<T> x, v;
  T rho, inv_rho;
  Sym3<T> s_rho2;  // sigma / rho^2
  T pressure;      // -tr(sigma) / 3
};

// Sums over a soil particle's neighbours, or one neighbour's share of them: acceleration (per
// unit neighbour mass), velocity gradient, kernel support (Shepard sum) and, for the effects that
// ask for it (kUsesDrift), the kernel-weighted velocity of the neighbours relative to the particle,
// sum V_j W_ij (v_j - v_i). These are the channels the CPU sums with SIMD (add_neighbours_simd,
// sph_neighbours.hpp).
template <typename T>
struct SoilSums {
  Vec3<T> acc{}, drift{};
  Mat3<T> L{};
  T support = 0;
  TERRACAL_HD SoilSums& operator+=(const SoilSums& o) {
    acc += o.acc;
    drift += o.drift;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) L.m[a][b] += o.L.m[a][b];
    support += o.support;
    return *this;
  }
};

// One neighbour j of a soil particle i, as the pair terms read it.
template <typename T>
struct Neighbour {
  Vec3<T> r;  // x_i - x_j
  T r2;
  typename SphKernel<T>::Values kv;  // W_ij and the gradient factor F (grad_i W_ij = F r)
  Vec3<T> grad;
  T inv_rho, vol;  // 1/rho_j, m/rho_j
  Vec3<T> dv;      // v_j - v_i
};

// What an effect's finish hook reads of a particle: its state and stress, its sums and the stage's step.
template <typename T>
struct ParticleUpdate {
  const SoilSelf<T>& me;
  const Sym3<T>& s;
  const SoilSums<T>& sum;
  T dt;
};

// Whether any effect of the list reads SoilSums::drift (highfi/crm/effects/crm_effect.hpp).
template <class Fx>
struct AnyUsesDrift;
template <class... E>
struct AnyUsesDrift<EffectList<E...>> : std::bool_constant<(E::kUsesDrift || ... || false)> {};

// EC below is the effects' constants (CrmEffectConstants<T>, highfi/crm/effects/crm_effects.hpp),
// a template parameter so that the effects can include this header.

// The acceleration that particle i receives from neighbour j per unit neighbour mass:
// (sigma_i/rho_i^2 + sigma_j/rho_j^2) . grad_i W_ij, plus the named effects' pair forces (the
// artificial viscosity). Used by the soil pass and, with the roles of soil and marker fixed, by the
// marker force pass, so that the forces on bodies are exactly the reaction of those on the soil.
// The caller supplies sigma_i/rho_i^2 (a soil particle's is worked out once, SoilSelf) and 1/rho_j^2,
// which it has from the one division per pair that also gives the volume m/rho_j.
template <typename T, class Fx, class EC>
TERRACAL_HD inline Vec3<T> pair_acceleration(const SphConstants<T>& k, const EC& ec, const Sym3<T>& si_rho2, T rho_i,
                                             const Vec3<T>& vi, const Sym3<T>& sj, T inv_rho2_j, T rho_j,
                                             const Vec3<T>& vj, const Vec3<T>& rij, T r2, const Vec3<T>& grad) {
  const Sym3<T> a = si_rho2 + inv_rho2_j * sj;
  Vec3<T> acc = a * grad;
  for_each_effect(Fx{}, [&](auto tag) {
    using E = typename decltype(tag)::type;
    E::pair_force(k, ec.template get<E>(), vi, rho_i, vj, rho_j, rij, r2, grad, acc);
  });
  return acc;
}

// The share of neighbour j (soil particle or boundary marker, within the support) in the sums of
// `me`; kSoil: j is a soil particle (the effects' soil-only terms apply). Records in and sums out
// by value, so that the CPU's SIMD loop keeps them in registers (GCC privatises any local whose
// address is taken inside an `omp simd` loop).
template <typename T, class Fx, bool kSoil, class EC>
TERRACAL_HD inline SoilSums<T> neighbour_share(const SphConstants<T>& k, const EC& ec, const SoilSelf<T>& me,
                                               Vec4<T> pj, Vec4<T> vj4, Vec4<T> s0j, Vec4<T> s1j) {
  Neighbour<T> nb;
  nb.r = me.x - pj.xyz();
  nb.r2 = dot(nb.r, nb.r);
  nb.kv = k.kernel.values(pair_sqrt(nb.r2));
  nb.grad = nb.kv.f * nb.r;
  const Vec3<T> vj = vj4.xyz();
  nb.inv_rho = pair_div(T(1), pj.w);
  nb.vol = k.mass * nb.inv_rho;
  nb.dv = vj - me.v;
  SoilSums<T> c;
  Sym3<T> sj = stress_of(s0j, s1j);
  if constexpr (!kSoil) sj = plus_pressure(sj, wall_contact_pressure_at(k, pair_sqrt(nb.r2), me.pressure));
  c.acc = pair_acceleration<T, Fx>(k, ec, me.s_rho2, me.rho, me.v, sj, nb.inv_rho * nb.inv_rho, pj.w, vj, nb.r, nb.r2,
                                   nb.grad);
  if constexpr (kSoil) {
    for_each_effect(Fx{}, [&](auto tag) {
      using E = typename decltype(tag)::type;
      E::pair_soil(k, ec.template get<E>(), me, nb, c);
    });
  }
  c.L = outer(nb.vol * nb.dv, nb.grad);
  c.support = nb.vol * nb.kv.w;
  if constexpr (AnyUsesDrift<Fx>::value) c.drift = (nb.vol * nb.kv.w) * nb.dv;
  return c;
}

// V_j W_ij: neighbour j's share of the kernel support of a particle at x, for the effects' own
// sums where the loop does not have it at hand (the CPU's SIMD sums do not return it per pair).
template <typename T>
TERRACAL_HD inline T support_share(const SphConstants<T>& k, const Vec3<T>& x, const Vec4<T>& pj) {
  const Vec3<T> r = x - pj.xyz();
  return k.mass / pj.w * k.kernel.values(std::sqrt(dot(r, r))).w;
}

}  // namespace terracal
