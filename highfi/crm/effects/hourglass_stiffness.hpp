#pragma once
// CRM effect `hourglass_stiffness`. The SPH velocity gradient does not see a checkerboard:
// neighbouring layers of particles that slide past each other in opposite directions strain
// nothing, so no stress resists them, and under a plate the soil escapes that way (why the rigs
// use it: docs/decisions.md). Each particle therefore keeps the displacement u that its
// neighbourhood's motion does not explain,
//   du_i/dt = v_i - vbar_i,   vbar_i = sum_n V_n W_in (v_n + L_i (x_i - x_n)) / S_i,   S_i = sum_n V_n W_in,
// over its neighbours n (soil and markers, not itself). Where the kernel is full (sum_n V_n W_in
// (x_i - x_n) = 0) vbar_i = v_i for any linear velocity field, so u stays zero under uniform strain
// and rigid motion; at a free surface, where the SPH gradient L_i falls short, it does not, but
// there the spring's frictional hold (below) is small. A spring of energy (m k / 2) |u_i|^2 pulls it
// back: the force -m k u_i on i, and its reaction m k (V_n W_in / S_i) u_i on each neighbour n, which
// sum to zero (momentum is conserved, and bodies feel their share through their markers).
// k = beta E / (rho0 h^2): a particle displaced by h from where its neighbours' motion puts it is
// pulled back as hard as a strain beta of the soil's Young modulus would push it.
// Its record per particle is (u, 1/S), w = 0 on the free surface, so that a neighbour reads u/S from
// one record.
#include <cmath>

#include "highfi/crm/effects/crm_effect.hpp"

namespace terracal {

struct HourglassStiffness : CrmEffect {
  static constexpr const char* kName = "hourglass_stiffness";
  static constexpr bool kInLoop = true;
  static constexpr bool kInMarkerLoop = true;
  static constexpr bool kRecord = true;
  static constexpr const char* kRecordName = "hg";
  static constexpr bool kListed = true;

  struct Settings {
    double beta = 0.03;
  };
  static constexpr auto settings() {
    return std::array{real_setting("beta", &Settings::beta, Range{0, 0.1, true, false},
                                   "spring k = beta E / (rho0 h^2) on the unexplained displacement")};
  }

  template <class T>
  struct Constants {
    T k;  // spring constant per unit mass [1/s^2]
  };
  template <class T>
  static Constants<T> constants(const Settings& s, const CrmEffectInput& in) {
    return {T(s.beta * in.soil.young_modulus / (in.soil.density * in.h * in.h))};
  }

  // Over a particle's neighbours: sum V W v_n, sum V W (x_i - x_n), sum W u_n / S_n (soil
  // neighbours), and S_i.
  template <class T>
  struct Sums {
    Vec3<T> wv{}, wr{}, react{};
    T ws = 0;
    TERRACAL_HD Sums& operator+=(const Sums& o) {
      wv += o.wv;
      wr += o.wr;
      react += o.react;
      ws += o.ws;
      return *this;
    }
  };
  // Neighbour n's share, from vw = V_n W_in and its record (u_n, 1/S_n), zero for a marker.
  template <class T>
  TERRACAL_HD_INLINE static Sums<T> share(const SphConstants<T>& k, const Vec3<T>& xi, const Vec4<T>& pn,
                                          const Vec4<T>& vn, T vw, const Vec4<T>& hg_n) {
    Sums<T> c;
    c.ws = vw;
    c.wv = vw * vn.xyz();
    c.wr = vw * (xi - pn.xyz());
    c.react = (pair_div(vw * pn.w, k.mass) * hg_n.w) * hg_n.xyz();  // W_in u_n / S_n
    return c;
  }
  template <class T>
  TERRACAL_HD_INLINE static void listed(const SphConstants<T>& k, const Constants<T>&, const Vec3<T>& xi,
                                        const Vec4<T>& pj, const Vec4<T>& vj, T vw, const Vec4<T>& record_j,
                                        Sums<T>& sums) {
    sums += share(k, xi, pj, vj, vw, record_j);
  }

  // The spring's force, and the new displacement: a free-surface particle (as for the stress)
  // keeps none.
  template <class T>
  TERRACAL_HD_INLINE static void finish(const SphConstants<T>& k, const Constants<T>& c, const Sums<T>& hs,
                                        const ParticleUpdate<T>& p, const Vec4<T>& record_eval,
                                        const Vec4<T>& record_base, Vec3<T>& acc, Vec3<T>&, Vec4<T>& record_out) {
    const SoilSelf<T>& me = p.me;
    acc += c.k * ((k.mass / me.rho) * hs.react - record_eval.xyz());
    if (p.sum.support >= k.free_surface_support && hs.ws > T(0)) {
      const T inv_s = T(1) / hs.ws;
      const Vec3<T> vbar = inv_s * (hs.wv + p.sum.L * hs.wr);
      Vec3<T> u = record_base.xyz() + p.dt * (me.v - vbar);
      // The spring is frictional, like the soil: it holds at most the force that the particle's
      // confinement gives a grain, (mu_s p + c) / (rho d0) per unit mass. Loose grains at the
      // surface are not held in place, and an error of the velocity extrapolation that keeps
      // feeding u (at a wall's corner) cannot build up a force that throws a particle out.
      T pressure = -p.s.trace() / T(3);
      pressure = pressure > T(0) ? pressure : T(0);
      const T u_max = (k.model.mu_s * pressure + k.model.cohesion) / (me.rho * k.spacing * c.k);
      const T u2 = dot(u, u);
      if (u2 > u_max * u_max) u = (u_max / std::sqrt(u2)) * u;
      record_out = make_vec4(u, inv_s);
    }
  }

  // The reaction of the soil particles' springs on a marker, m k V_m sum_j W u_j / S_j.
  template <class T>
  struct MarkerSums {
    Vec3<T> react{};
  };
  template <class T>
  TERRACAL_HD_INLINE static void marker_pair(const SphConstants<T>&, const Constants<T>&, T w, const Vec4<T>& record_j,
                                             MarkerSums<T>& s) {
    s.react += (w * record_j.w) * record_j.xyz();
  }
  template <class T>
  TERRACAL_HD_INLINE static void marker_finish(const SphConstants<T>&, const Constants<T>& c, T rho_m,
                                               const MarkerSums<T>& s, Vec3<T>& f) {
    f += (c.k / rho_m) * s.react;
  }
};

}  // namespace terracal
