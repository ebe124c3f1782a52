#pragma once
// One midpoint stage for one soil particle, written once for both backends (docs/architecture.md, "CRM"):
// sum the momentum balance, the velocity gradient and the kernel support over the soil and marker
// neighbours, let the named effects add their terms, then integrate and return-map the stress.
// Fx is the compile-time list of the named effects with terms in this pass (CrmEffect::kInLoop):
// the stage is compiled for each such list, so an effect a scene does not name is not in its code.
//
// A stage evaluates the rates at the `eval` state and writes out = base + dt * rate. The midpoint
// step is stage(A -> B, dt/2) followed by stage(B -> A, dt): the second stage reads B and updates
// A in place, which is safe because a particle reads only its own record of A.
#include "highfi/crm/soil_arrays.hpp"
#include "highfi/crm/sph_neighbours.hpp"

namespace terracal {

template <typename T, class Fx>
struct SoilStage {
  // CUDA blocks of 256 per SM the stage is compiled for: 4 caps it at 64 registers, which suits the
  // core sums; effects with sums of their own (hourglass_stiffness) then spill, and 3 (80 registers)
  // runs the rigs' configuration 1.28x faster (docs/decisions.md, "CUDA launch bounds").
  static constexpr int kCudaMinBlocks = AnyListed<Fx>::value ? 3 : 4;
  SphConstants<T> k;
  CrmEffectConstants<T> ec;
  GridGeometry<T> grid;
  const int* soil_begin;
  const int* marker_begin;
  SoilArrays<T> eval, base, out;
  MarkerArrays<T> mk;
  T dt;

  TERRACAL_HD void operator()(long i) const { run(i, SingleLane{}); }
  // Particle i with a group of GPU lanes (core/lane_group.hpp): each lane walks a share of the rows,
  // the group adds up the sums, and its leader updates the particle.
  TERRACAL_HD void operator()(long i, const LaneGroup& g) const { run(i, g); }

  template <class G>
  TERRACAL_HD void run(long i, const G& g) const {
    const Vec4<T> vb = base.vel[i];
    if (vb.w != T(kParticleActive)) {  // frozen (outside the active domain) or lost: carried unchanged
      if (g.leader()) carry(i, vb);
      return;
    }
    const SoilSelf<T> me = self(i);
    SoilSums<T> sum;
    if (g.leader()) sum.support = k.mass / me.rho * k.kernel.values(T(0)).w;
    EffectSums<T, Fx> own;
#if defined(__CUDA_ARCH__)
    add_neighbours_gpu(i, me, sum, own, g);
    g.template sum<T>(sum);
    g.template sum<T>(own);
    if (!g.leader()) return;
#else
    add_neighbours_cpu(i, me, sum, own);
#endif
    update(i, vb, me, sum, own);
  }

  // The frozen and lost particles' part of the stage alone, for backends that run the active ones
  // from a list (B::kCompactsActive).
  struct CarryFrozen {
    SoilStage stage;
    TERRACAL_HD void operator()(long i) const {
      const Vec4<T> vb = stage.base.vel[i];
      if (vb.w != T(kParticleActive)) stage.carry(i, vb);
    }
  };

  TERRACAL_HD void carry(long i, const Vec4<T>& vb) const {
    if (base.pos == out.pos) return;
    out.pos[i] = base.pos[i];
    out.vel[i] = vb;
    out.s0[i] = base.s0[i];
    out.s1[i] = base.s1[i];
    for_each_effect(Fx{}, [&](auto tag) {
      using E = typename decltype(tag)::type;
      if constexpr (E::kRecord) out.record[kRecordSlot<E>][i] = base.record[kRecordSlot<E>][i];
    });
  }

  TERRACAL_HD SoilSelf<T> self(long i) const {
    const Vec4<T> pi4 = eval.pos[i];
    SoilSelf<T> me;
    me.x = pi4.xyz();
    me.v = eval.vel[i].xyz();
    me.rho = pi4.w;
    me.inv_rho = T(1) / me.rho;
    const Sym3<T> s = stress_of(eval.s0[i], eval.s1[i]);
    me.s_rho2 = (me.inv_rho * me.inv_rho) * s;
    me.pressure = -s.trace() / T(3);
    return me;
  }

#if defined(__CUDA_ARCH__)
  // GPU: a thread (or its share of a lane group's rows) walks the particle's neighbour rows, testing a
  // row before summing its hits.
  template <class G>
  __device__ void add_neighbours_gpu(long i, const SoilSelf<T>& me, SoilSums<T>& sum, EffectSums<T, Fx>& own,
                                     const G& g) const {
    const T support2 = k.kernel.support2();
    grid.for_each_neighbour_range(me.x, soil_begin, g, [&](int first, int last) {
      for_each_hit(eval.pos, first, last, int(i), me.x, support2, [&](int j) {
        const Vec4<T> pj = load(eval.pos + j), vj = load(eval.vel + j);
        const SoilSums<T> c = neighbour_share<T, Fx, true>(k, ec, me, pj, vj, load(eval.s0 + j), load(eval.s1 + j));
        sum += c;
        add_listed<T, Fx>(
            k, ec, me.x, pj, vj, c.support, [&](int slot) { return load(eval.record[slot] + j); }, own);
      });
    });
    grid.for_each_neighbour_range(me.x, marker_begin, g, [&](int first, int last) {
      for_each_hit(mk.pos, first, last, -1, me.x, support2, [&](int j) {
        const Vec4<T> pj = load(mk.pos + j), vj = load(mk.vel + j);
        const SoilSums<T> c = neighbour_share<T, Fx, false>(k, ec, me, pj, vj, load(mk.s0 + j), load(mk.s1 + j));
        sum += c;
        add_listed<T, Fx>(
            k, ec, me.x, pj, vj, c.support, [](int) { return Vec4<T>{}; }, own);
      });
    });
  }
#else
  // CPU: list the neighbours within the support (branch-free), then sum them with SIMD; the
  // effects' own sums follow in a scalar pass over the same list. The list is flushed whenever it
  // fills, so any number of neighbours is handled.
  void add_neighbours_cpu(long i, const SoilSelf<T>& me, SoilSums<T>& sum, EffectSums<T, Fx>& own) const {
    const T support2 = k.kernel.support2();
    constexpr int kChunk = kSimdChunk;
    int list[kChunk + 8];  // + 8: filter_row stores 8 entries at a time
    int n = 0;
    auto collect = [&](const Vec4<T>* pos, int first, int last, long self, auto&& flush) {
      while (first < last) {
        if (n > kChunk - 16) {
          flush();
          n = 0;
        }
        const int room = kChunk - n;
        const int stop = last - first < room ? last : first + room;
        n = filter_row(pos, first, stop, self, me.x, support2, list, n);
        first = stop;
      }
    };
    auto flush_soil = [&] {
      add_neighbours_simd<T, Fx, true>(sum, k, ec, me, eval.pos, eval.vel, eval.s0, eval.s1, list, n);
      if constexpr (AnyListed<Fx>::value)
        for (int q = 0; q < n; ++q) {
          const int j = list[q];
          add_listed<T, Fx>(
              k, ec, me.x, eval.pos[j], eval.vel[j], support_share(k, me.x, eval.pos[j]),
              [&](int slot) { return eval.record[slot][j]; }, own);
        }
    };
    grid.for_each_neighbour_range(me.x, soil_begin,
                                  [&](int first, int last) { collect(eval.pos, first, last, i, flush_soil); });
    flush_soil();
    n = 0;
    auto flush_markers = [&] {
      add_neighbours_simd<T, Fx, false>(sum, k, ec, me, mk.pos, mk.vel, mk.s0, mk.s1, list, n);
      if constexpr (AnyListed<Fx>::value)
        for (int q = 0; q < n; ++q) {
          const int j = list[q];
          add_listed<T, Fx>(
              k, ec, me.x, mk.pos[j], mk.vel[j], support_share(k, me.x, mk.pos[j]), [](int) { return Vec4<T>{}; }, own);
        }
    };
    grid.for_each_neighbour_range(me.x, marker_begin,
                                  [&](int first, int last) { collect(mk.pos, first, last, -1, flush_markers); });
    flush_markers();
  }
#endif

  // The effects' per-particle terms, then the midpoint update of position, density, velocity and
  // stress, the return map, and the records the effects keep.
  TERRACAL_HD void update(long i, const Vec4<T>& vb, const SoilSelf<T>& me, const SoilSums<T>& sum,
                          const EffectSums<T, Fx>& own) const {
    const Mat3<T>& L = sum.L;
    Vec3<T> acc = k.mass * sum.acc + k.gravity;
    Vec3<T> drift = me.v;
    Vec4<T> records[kCrmRecordSlots] = {};
    // The stress at eval, read again: the neighbour loop needs only sigma / rho^2 (SoilSelf).
    const Sym3<T> s_eval = stress_of(eval.s0[i], eval.s1[i]);
    const ParticleUpdate<T> p{me, s_eval, sum, dt};
    for_each_effect(Fx{}, [&](auto tag) {
      using E = typename decltype(tag)::type;
      Vec4<T> at_eval{}, at_base{}, next{};
      if constexpr (E::kRecord) {
        at_eval = eval.record[kRecordSlot<E>][i];
        at_base = base.record[kRecordSlot<E>][i];
      }
      E::finish(k, ec.template get<E>(), own.template get<E>(), p, at_eval, at_base, acc, drift, next);
      if constexpr (E::kRecord) records[kRecordSlot<E>] = next;
    });
    const T div_v = L.m[0][0] + L.m[1][1] + L.m[2][2];
    const Sym3<T> rate = jaumann_rate(s_eval, L, k.model);

    const Vec4<T> pb = base.pos[i];
    const Vec4<T> s0b = base.s0[i], s1b = base.s1[i];
    const Vec3<T> x_new = pb.xyz() + dt * drift;
    T rho_new = pb.w - dt * me.rho * div_v;
    const Vec3<T> v_new = vb.xyz() + dt * acc;
    Sym3<T> s_new = stress_of(s0b, s1b) + dt * rate;
    T plastic = s1b.z + return_map(s_new, shear_rate(L), k.model);
    // A particle with a truncated kernel (free surface) cannot resolve its velocity gradient;
    // it carries no stress rather than a spurious one.
    if (sum.support < k.free_surface_support) s_new = Sym3<T>{};
    // Soil does not compress without bound where the tie of density to pressure is lost (density_cap).
    const T rho_cap = density_cap(-s_new.trace() / T(3), k.model);
    if (rho_new > rho_cap) rho_new = rho_cap;
    out.pos[i] = make_vec4(x_new, rho_new);
    out.vel[i] = make_vec4(v_new, T(kParticleActive));
    out.s0[i] = {s_new.xx, s_new.yy, s_new.zz, s_new.xy};
    out.s1[i] = {s_new.xz, s_new.yz, plastic, sum.support};
    for_each_effect(Fx{}, [&](auto tag) {
      using E = typename decltype(tag)::type;
      if constexpr (E::kRecord) out.record[kRecordSlot<E>][i] = records[kRecordSlot<E>];
    });
  }
};

}  // namespace terracal
