#pragma once
// The two backends' neighbour loops (docs/architecture.md, "CRM"): the arithmetic of a pair is
// sph_pair.hpp's, written once; only the loop differs, because the two machines want different loops.
// - GPU: one thread walks its rows of cells, tests a row of candidates first and keeps the hits as a
//   bit mask, then sums the hits (for_each_hit).
// - CPU: a particle's neighbours are listed by an AVX2 filter (neighbour_filter_cpu.hpp), copied into
//   structure-of-arrays form and summed 8 at a time under `omp simd` (add_neighbours_simd).
// Both also call the named effects' own pair sums (add_listed).
#include "highfi/crm/effects/crm_effects.hpp"
#include "highfi/crm/sph_pair.hpp"
#if !defined(__CUDA_ARCH__)
#include "highfi/crm/neighbour_filter_cpu.hpp"
#endif

namespace terracal {

// The effects' own sums over a particle's neighbours (PerEffect of each effect's Sums<T>).
template <class T, class Fx>
using EffectSums = PerEffect<EffectSumsIn<T>::template of, Fx>;

// Whether any effect of the list has sums of its own (CrmEffect::kListed).
template <class Fx>
struct AnyListed;
template <class... E>
struct AnyListed<EffectList<E...>> : std::bool_constant<(E::kListed || ... || false)> {};

// Neighbour j's share in the effects' own sums: at pj with velocity vj, share vw = V_j W_ij of the
// support; record_of(slot) reads its record of an effect (kRecord), zero for a marker.
template <class T, class Fx, class RecordOf>
TERRACAL_HD_INLINE void add_listed(const SphConstants<T>& k, const CrmEffectConstants<T>& ec, const Vec3<T>& xi,
                                   const Vec4<T>& pj, const Vec4<T>& vj, T vw, const RecordOf& record_of,
                                   EffectSums<T, Fx>& own) {
  for_each_effect(Fx{}, [&](auto tag) {
    using E = typename decltype(tag)::type;
    if constexpr (E::kListed) {
      Vec4<T> record{};
      if constexpr (E::kRecord) record = record_of(kRecordSlot<E>);
      E::listed(k, ec.template get<E>(), xi, pj, vj, vw, record, own.template get<E>());
    }
  });
}

#if !defined(__CUDA_ARCH__)
// The CPU's inner loop. The neighbours listed in `list` (at most kSimdChunk, all within the support;
// room for 8 more) are first copied into structure-of-arrays form, then summed with SIMD across
// neighbours: x86 gathers are slow, contiguous loads are not. The reductions are written out one
// scalar per channel of SoilSums, so that GCC vectorises them (it does not vectorise a reduction
// into a struct).
constexpr int kSimdChunk = 128;
template <typename T, class Fx, bool kSoil>
inline void add_neighbours_simd(SoilSums<T>& sum, const SphConstants<T>& k, const CrmEffectConstants<T>& ec,
                                const SoilSelf<T>& me, const Vec4<T>* pos, const Vec4<T>* vel, const Vec4<T>* s0,
                                const Vec4<T>* s1, int* list, int n) {
  alignas(64) T px[kSimdChunk + 8], py[kSimdChunk + 8], pz[kSimdChunk + 8], pr[kSimdChunk + 8];
  alignas(64) T vx[kSimdChunk + 8], vy[kSimdChunk + 8], vz[kSimdChunk + 8];
  alignas(64) T sxx[kSimdChunk + 8], syy[kSimdChunk + 8], szz[kSimdChunk + 8], sxy[kSimdChunk + 8], sxz[kSimdChunk + 8],
      syz[kSimdChunk + 8];
  T* const staged[kStagedFields] = {px, py, pz, pr, vx, vy, vz, sxx, syy, szz, sxy, sxz, syz};
  stage_neighbours(pos, vel, s0, s1, list, n, staged);
  // The effects' constants in this frame: an effect may read them under a condition (the artificial
  // viscosity, only for approaching pairs), and GCC neither hoists nor vectorises a conditional load
  // through a reference it cannot prove safe; from a local it does both.
  const CrmEffectConstants<T> effect_constants = ec;
  T ax = 0, ay = 0, az = 0, dx = 0, dy = 0, dz = 0, sup = 0;
  T l00 = 0, l01 = 0, l02 = 0, l10 = 0, l11 = 0, l12 = 0, l20 = 0, l21 = 0, l22 = 0;
#pragma omp simd reduction(+ : ax, ay, az, dx, dy, dz, sup, l00, l01, l02, l10, l11, l12, l20, l21, l22)
  for (int q = 0; q < n; ++q) {
    const SoilSums<T> c = neighbour_share<T, Fx, kSoil>(
        k, effect_constants, me, Vec4<T>{px[q], py[q], pz[q], pr[q]}, Vec4<T>{vx[q], vy[q], vz[q], T(0)},
        Vec4<T>{sxx[q], syy[q], szz[q], sxy[q]}, Vec4<T>{sxz[q], syz[q], T(0), T(0)});
    ax += c.acc.x;
    ay += c.acc.y;
    az += c.acc.z;
    dx += c.drift.x;
    dy += c.drift.y;
    dz += c.drift.z;
    sup += c.support;
    l00 += c.L.m[0][0];
    l01 += c.L.m[0][1];
    l02 += c.L.m[0][2];
    l10 += c.L.m[1][0];
    l11 += c.L.m[1][1];
    l12 += c.L.m[1][2];
    l20 += c.L.m[2][0];
    l21 += c.L.m[2][1];
    l22 += c.L.m[2][2];
  }
  sum.acc += Vec3<T>{ax, ay, az};
  sum.drift += Vec3<T>{dx, dy, dz};
  sum.support += sup;
  const T l[3][3] = {{l00, l01, l02}, {l10, l11, l12}, {l20, l21, l22}};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) sum.L.m[a][b] += l[a][b];
}
#endif

#if defined(__CUDA_ARCH__)
// The GPU's neighbour loop over one row of cells: the candidates are tested first and the hits
// kept as a bit mask, then f(j) runs for each hit. The lanes of a warp thus run the heavy pair
// arithmetic once per hit of the lane with most hits, not once per candidate of the longest row
// (about one candidate in four is a hit).
template <typename T, typename F>
__device__ inline void for_each_hit(const Vec4<T>* pos, int first, int last, int self, const Vec3<T>& x, T support2,
                                    F&& f) {
  for (int base = first; base < last; base += 32) {
    const int end = last - base < 32 ? last : base + 32;
    unsigned hits = 0;
    for (int j = base; j < end; ++j) {
      const Vec3<T> r = x - load(pos + j).xyz();
      hits |= unsigned(dot(r, r) < support2 && j != self) << (j - base);
    }
    while (hits) {
      const int j = base + __ffs(int(hits)) - 1;
      hits &= hits - 1;
      f(j);
    }
  }
}
#endif

}  // namespace terracal
