#pragma once
// Boundary markers (Adami et al. 2012), written once for both backends: the stress (and the
// velocity) of each marker extrapolated from the soil around it, then the force of the soil on the
// marker, which the host sums into body wrenches. Mx is the compile-time list of the named effects
// with terms in this pass (CrmEffect::kInMarkerLoop).
#include "highfi/crm/soil_arrays.hpp"
#include "highfi/crm/sph_neighbours.hpp"
#include "highfi/crm/wall_contact.hpp"

namespace terracal {

// MarkerVelocity::kMirrorContact: a soil particle whose centre is further than this many spacings
// from the wall's surface is not in contact (one in contact sits half a spacing from it).
constexpr double kContactFade = 0.65;

// What the soil sees of a marker: its extrapolated stress and velocity, and its density.
template <typename T>
struct MarkerSoilView {
  Sym3<T> s;
  Vec3<T> v;
  T rho, inv_rho2;
};

template <typename T, class Mx>
struct MarkerStage {
  SphConstants<T> k;
  CrmEffectConstants<T> ec;
  GridGeometry<T> grid;
  const int* soil_begin;
  SoilArrays<T> soil;  // the state the stage is evaluated at
  MarkerArrays<T> mk;
  const BodyPose<T>* poses;  // to turn the wall normals of MarkerVelocity::kMirrorImage into the world frame
  // The active domain's boxes (count 0: none). A marker farther than box_reach from all of them (the
  // kernel's support, plus the drift an active particle may stray from its box with a sort skin) has
  // only frozen neighbours, which read nothing: it is skipped, and exerts no force.
  const ActiveBox<T>* boxes;
  int box_count;
  T box_reach;

  TERRACAL_HD void operator()(long m) const { run(m, SingleLane{}); }
  // Marker m with a group of GPU lanes (core/lane_group.hpp): each lane walks a share of the rows,
  // the group adds up the sums, and its leader writes the marker.
  TERRACAL_HD void operator()(long m, const LaneGroup& g) const { run(m, g); }

  template <class G>
  TERRACAL_HD void run(long m, const G& g) const {
    const Vec3<T> xm = mk.pos[m].xyz();
    const T support2 = k.kernel.support2();
    if (!near_active(boxes, box_count, xm, box_reach)) {
      if (g.leader()) mk.force[m] = Vec4<T>{T(0), T(0), T(0), T(0)};
      return;
    }
    // visit(f) calls f(j) for every soil particle j within the support of the marker, twice per
    // marker (extrapolation, then force).
#if defined(__CUDA_ARCH__)
    auto visit = [&](auto&& f) {
      grid.for_each_neighbour_range(
          xm, soil_begin, g, [&](int first, int last) { for_each_hit(soil.pos, first, last, -1, xm, support2, f); });
    };
#else
    // The CPU lists the neighbours once (SIMD filter) and walks the list in both passes; a marker
    // buried in an unusually dense heap falls back to walking the cells.
    constexpr int kCapacity = 256;
    int list[kCapacity + 8];
    int n = 0;
    bool listed = true;
    grid.for_each_neighbour_range(xm, soil_begin, [&](int first, int last) {
      if (!listed || n + (last - first) > kCapacity) {
        listed = false;
        return;
      }
      n = filter_row(soil.pos, first, last, -1, xm, support2, list, n);
    });
    auto visit = [&](auto&& f) {
      if (listed) {
        for (int q = 0; q < n; ++q) f(list[q]);
        return;
      }
      grid.for_each_neighbour_range(xm, soil_begin, [&](int first, int last) {
        for (int j = first; j < last; ++j) {
          const Vec3<T> r = xm - soil.pos[j].xyz();
          if (dot(r, r) < support2) f(j);
        }
      });
    };
#endif
    force(m, extrapolate(m, visit, g), visit, g);
  }

  // The marker's stress and velocity, extrapolated from the soil around it (written to mk).
  template <class Visit, class G>
  TERRACAL_HD MarkerSoilView<T> extrapolate(long m, const Visit& visit, const G& g) const {
    const Vec4<T> pm = mk.pos[m];
    const Vec3<T> xm = pm.xyz();
    const Vec4<T> wv = mk.wall_vel[m];
    T sum_w = 0;
    Sym3<T> sum_s{};
    Vec3<T> sum_v{}, sum_rho_r{};
    // kMirrorContact: the marker's depth a below the wall's surface, and the least distance from that
    // surface of a soil particle, taken as (distance from the marker) - a: exact for the particle in
    // front of the marker, larger for one beside it. It needs no normal, which the middle layer of a
    // thin plate does not have (equally deep below both faces).
    const bool contact_rule = k.marker_velocity == MarkerVelocity::kMirrorContact;
    const T depth = contact_rule ? mk.normal[m].w : T(0);
    const T d0 = k.spacing;
    T gap = T(1e30);
    visit([&](int j) {
      const Vec4<T> pj = soil.pos[j];
      const Vec3<T> r = xm - pj.xyz();
      const T dist = pair_sqrt(dot(r, r));
      if (contact_rule && dist - depth < gap) gap = dist - depth;
      const T w = k.kernel.values(dist).w;
      sum_w += w;
      sum_s = sum_s + w * stress_of(soil.s0[j], soil.s1[j]);
      sum_v += w * soil.vel[j].xyz();
      sum_rho_r += (w * pj.w) * r;
    });
    g.template sum<T>(sum_w);
    g.template sum<T>(sum_s);
    g.template sum<T>(sum_v);
    g.template sum<T>(sum_rho_r);
    if (contact_rule) g.min(gap);
    Sym3<T> sm{};
    Vec3<T> vm = wv.xyz();
    if (sum_w > T(0)) {
      const T inv = T(1) / sum_w;
      // sigma_m = <sigma> - I (g - a_wall).<rho r>: the hydrostatic head between soil and marker.
      // Wall acceleration is neglected (prescribed bodies move at constant velocity).
      const T head = dot(k.gravity, sum_rho_r) * inv;
      sm = inv * sum_s;
      sm.xx -= head;
      sm.yy -= head;
      sm.zz -= head;
      // Adami's mirror velocity, or the wall's own (see MarkerVelocity).
      if (k.marker_velocity != MarkerVelocity::kWall) vm = T(2) * wv.xyz() - inv * sum_v;
      if (contact_rule && depth > T(0)) {
        // A particle in contact has its centre half a spacing from the wall; the mirror fades out
        // as the gap grows to 0.15 spacings more, and the marker then moves with the soil.
        T phi = (T(kContactFade) * d0 - gap) / ((T(kContactFade) - T(0.5)) * d0);
        phi = phi < T(0) ? T(0) : (phi > T(1) ? T(1) : phi);
        vm = phi * vm + (T(1) - phi) * (inv * sum_v);
      }
    }
    if (k.marker_velocity == MarkerVelocity::kMirrorImage) vm = mirror_image_velocity(m, xm, wv.xyz(), vm);
    const T rho_m = pm.w, inv_rho2_m = T(1) / (rho_m * rho_m);
    if (g.leader()) {
      mk.vel[m] = make_vec4(vm, T(0));
      mk.s0[m] = {sm.xx, sm.yy, sm.zz, sm.xy};
      mk.s1[m] = {sm.xz, sm.yz, T(0), sum_w};
    }
    return {sm, vm, rho_m, inv_rho2_m};
  }

  // Force of the soil on the marker: minus what the marker does to each soil particle (with the
  // effects' pair forces), plus the effects' marker terms (the reaction of hourglass_stiffness's
  // springs), from the same kernel values.
  template <class Visit, class G>
  TERRACAL_HD void force(long m, const MarkerSoilView<T>& ms, const Visit& visit, const G& g) const {
    const Vec3<T> xm = mk.pos[m].xyz();
    PerEffect<EffectSumsIn<T>::template marker, Mx> own;
    Vec3<T> f{};
    visit([&](int j) {
      const Vec4<T> pj = soil.pos[j];
      const Vec3<T> r = pj.xyz() - xm;  // from the soil particle's side: r_jm
      const T r2 = dot(r, r);
      const T dist = pair_sqrt(r2);
      const typename SphKernel<T>::Values kv = k.kernel.values(dist);
      const T rho_j = pj.w;
      const Sym3<T> sj = stress_of(soil.s0[j], soil.s1[j]);
      // The marker's stress as soil particle j sees it: with the contact pressure (wall_contact.hpp).
      const Sym3<T> sm = plus_pressure(ms.s, wall_contact_pressure(k, dist, sj));
      f -= pair_acceleration<T, Mx>(k, ec, pair_div(T(1), rho_j * rho_j) * sj, rho_j, soil.vel[j].xyz(), sm,
                                    ms.inv_rho2, ms.rho, ms.v, r, r2, kv.f * r);
      for_each_effect(Mx{}, [&](auto tag) {
        using E = typename decltype(tag)::type;
        Vec4<T> record{};
        if constexpr (E::kRecord) record = soil.record[kRecordSlot<E>][j];
        E::marker_pair(k, ec.template get<E>(), kv.w, record, own.template get<E>());
      });
    });
    g.template sum<T>(f);
    g.template sum<T>(own);
    for_each_effect(Mx{}, [&](auto tag) {
      using E = typename decltype(tag)::type;
      E::marker_finish(k, ec.template get<E>(), ms.rho, own.template get<E>(), f);
    });
    if (g.leader()) mk.force[m] = make_vec4((k.mass * k.mass) * f, T(0));
  }

  // The marker's wall normal in the world frame, w = its depth (0: none).
  TERRACAL_HD Vec4<T> world_normal(long m) const {
    const Vec4<T> nl = mk.normal[m];
    if (!(nl.w > T(0))) return Vec4<T>{};
    const BodyPose<T>& b = poses[int(mk.local[m].w)];
    return {b.R[0] * nl.x + b.R[1] * nl.y + b.R[2] * nl.z, b.R[3] * nl.x + b.R[4] * nl.y + b.R[5] * nl.z,
            b.R[6] * nl.x + b.R[7] * nl.y + b.R[8] * nl.z, nl.w};
  }

  // The mirror of the soil's velocity at the marker's image x* = x_m + 2 a n across the wall:
  // v_m = v_wall(x_m) + v_rigid(x*) - v(x*), which for a wall at rest is -v(x*), and for a wall moving
  // rigidly maps a soil that moves with it onto the wall's own motion. v(x*) is a linear moving-least-
  // squares fit to the soil around x*: a Shepard average would be biased towards the deeper soil where
  // x* lies near the wall and its kernel is cut (the first marker layer's image lies half a spacing
  // into the soil), and so over-extrapolate there. Where x* has less than the kernel support of a half
  // space around it (a rim, a corner, an image past the free surface), or the fit is ill-conditioned,
  // the result blends into Adami's average `adami` between supports of 0.3 and 0.7, so that nothing
  // jumps as a body moves.
  TERRACAL_HD Vec3<T> mirror_image_velocity(long m, const Vec3<T>& xm, const Vec3<T>& v_wall,
                                            const Vec3<T>& adami) const {
    const Vec4<T> nw = world_normal(m);
    if (!(nw.w > T(0)) || !(dot(nw.xyz(), nw.xyz()) > T(0.5))) return adami;  // no normal: no image
    const BodyPose<T>& b = poses[int(mk.local[m].w)];
    const Vec3<T> off = (T(2) * nw.w) * nw.xyz();
    const Vec3<T> xs = xm + off;
    const T support2 = k.kernel.support2();
    // Moments of the fit in offsets scaled by 1/h: A = sum w [1 d][1 d]^T (4x4), rhs = sum w v [1 d].
    T A[4][4] = {}, rhs[3][4] = {};
    T support = 0;
    grid.for_each_neighbour_range(xs, soil_begin, [&](int first, int last) {
      for (int j = first; j < last; ++j) {
        const Vec4<T> pj = soil.pos[j];
        const Vec3<T> r = pj.xyz() - xs;
        const T r2 = dot(r, r);
        if (r2 < support2) {
          const T w = k.kernel.values(std::sqrt(r2)).w;
          support += k.mass / pj.w * w;
          const T q[4] = {T(1), r.x * k.kernel.inv_h, r.y * k.kernel.inv_h, r.z * k.kernel.inv_h};
          const Vec3<T> v = soil.vel[j].xyz();
          for (int a = 0; a < 4; ++a) {
            for (int c = a; c < 4; ++c) A[a][c] += w * q[a] * q[c];
            rhs[0][a] += w * v.x * q[a];
            rhs[1][a] += w * v.y * q[a];
            rhs[2][a] += w * v.z * q[a];
          }
        }
      }
    });
    T beta = (support - T(0.3)) / T(0.4);
    beta = beta < T(0) ? T(0) : (beta > T(1) ? T(1) : beta);
    if (!(beta > T(0))) return adami;
    for (int a = 0; a < 4; ++a)
      for (int c = 0; c < a; ++c) A[a][c] = A[c][a];
    // v(x*) is the constant term of the fit: the first component of A^-1 rhs, by Gaussian elimination
    // (A is symmetric positive definite when the neighbours are not all in one plane).
    const T scale = A[0][0];
    for (int col = 0; col < 4; ++col) {
      const T piv = A[col][col];
      if (!(piv > T(1e-6) * scale)) return adami;
      for (int row = col + 1; row < 4; ++row) {
        const T f = A[row][col] / piv;
        for (int c = col; c < 4; ++c) A[row][c] -= f * A[col][c];
        for (int comp = 0; comp < 3; ++comp) rhs[comp][row] -= f * rhs[comp][col];
      }
    }
    T v_star[3];
    for (int comp = 0; comp < 3; ++comp) {
      T x[4];
      for (int row = 3; row >= 0; --row) {
        T acc = rhs[comp][row];
        for (int c = row + 1; c < 4; ++c) acc -= A[row][c] * x[c];
        x[row] = acc / A[row][row];
      }
      v_star[comp] = x[0];
    }
    const Vec3<T> v_rigid = v_wall + cross(b.omega, off);
    const Vec3<T> image = v_wall + v_rigid - Vec3<T>{v_star[0], v_star[1], v_star[2]};
    return beta * image + (T(1) - beta) * adami;
  }
};

}  // namespace terracal
