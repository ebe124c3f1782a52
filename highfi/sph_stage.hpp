#pragma once
// The per-particle physics of one Runge-Kutta stage, written once for both backends
// (DESIGN.md §4). Each functor is called as f(i) by parallel_for on the CPU or in a CUDA kernel.
//
// A stage evaluates the rates at the `eval` state and writes out = base + dt * rate. The midpoint
// step is stage(A -> B, dt/2) followed by stage(B -> A, dt): the second stage reads B and updates
// A in place, which is safe because a particle reads only its own record of A.
#include "highfi/sph_fields.hpp"
#if !defined(__CUDA_ARCH__)
#include "highfi/neighbour_filter_cpu.hpp"
#endif

namespace terracal {

// The acceleration that particle i receives from neighbour j per unit neighbour mass:
// (sigma_i/rho_i^2 + sigma_j/rho_j^2) . grad_i W_ij  -  Pi_ij grad_i W_ij  (Monaghan viscosity).
// Used by the soil pass and, with the roles of soil and marker fixed, by the marker force pass, so
// that the forces on bodies are exactly the reaction of those on the soil. The caller supplies
// 1/rho_j^2, which it has from the one division per pair that also gives the volume m/rho_j.
template <typename T, bool kViscosity>
TERRACAL_HD inline Vec3<T> pair_acceleration(const SphConstants<T>& k, const Sym3<T>& si, T inv_rho2_i, T rho_i,
                                             const Vec3<T>& vi, const Sym3<T>& sj, T inv_rho2_j, T rho_j,
                                             const Vec3<T>& vj, const Vec3<T>& rij, T r2, const Vec3<T>& grad) {
  const Sym3<T> a = inv_rho2_i * si + inv_rho2_j * sj;
  Vec3<T> acc = a * grad;
  if (kViscosity) {
    const T vr = dot(vi - vj, rij);
    if (vr < T(0)) {
      // Pi = -alpha c mu / rho_mean with mu = h vr / (r^2 + 0.01 h^2), in one division.
      const T h = k.kernel.h;
      const T pi = T(-2) * k.viscosity_alpha * k.sound_speed * h * vr / ((r2 + T(0.01) * h * h) * (rho_i + rho_j));
      acc -= pi * grad;
    }
  }
  return acc;
}

// A soil particle's own state, as the sums over its neighbours need it.
template <typename T>
struct SoilSelf {
  Vec3<T> x, v;
  T rho, inv_rho, inv_rho2;
  Sym3<T> s;
};

// Sums over a soil particle's neighbours, or one neighbour's share of them: acceleration (per
// unit mass), velocity gradient, kernel support (Shepard sum) and the XSPH drift.
template <typename T>
struct SoilSums {
  Vec3<T> acc{}, xsph{};
  Mat3<T> L{};
  T support = 0;
  TERRACAL_HD SoilSums& operator+=(const SoilSums& o) {
    acc += o.acc;
    xsph += o.xsph;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) L.m[a][b] += o.L.m[a][b];
    support += o.support;
    return *this;
  }
};

// The share of neighbour j (soil particle or boundary marker, within the support) in the sums of
// `me`. Records in and sums out by value, so that the CPU's SIMD loop keeps them in registers
// (GCC privatises any local whose address is taken inside an `omp simd` loop into memory).
// kHourglass adds the hourglass damping between soil particles (the caller passes false for markers).
template <typename T, bool kViscosity, bool kShifting, bool kHourglass>
TERRACAL_HD inline SoilSums<T> neighbour_share(const SphConstants<T>& k, const SoilSelf<T>& me, Vec4<T> pj, Vec4<T> vj4,
                                               Vec4<T> s0j, Vec4<T> s1j) {
  const Vec3<T> r = me.x - pj.xyz();
  const T r2 = dot(r, r);
  const typename SphKernel<T>::Values kv = k.kernel.values(std::sqrt(r2));
  const Vec3<T> grad = kv.f * r;
  const Vec3<T> vj = vj4.xyz();
  const T inv_rho_j = T(1) / pj.w;
  const T vol_j = k.mass * inv_rho_j;
  const Vec3<T> dv = vj - me.v;
  SoilSums<T> c;
  c.acc = pair_acceleration<T, kViscosity>(k, me.s, me.inv_rho2, me.rho, me.v, stress_of(s0j, s1j),
                                           inv_rho_j * inv_rho_j, pj.w, vj, r, r2, grad);
  if (kHourglass) {
    // Morris' SPH Laplacian nu lap(v) on the whole relative velocity. It vanishes on any linear
    // velocity field (interior, symmetric neighbourhood), so uniform strain rates and rigid
    // rotation go undamped, but it damps the lattice's checkerboard modes, in which neighbours
    // move past each other and which neither the velocity gradient nor the artificial viscosity
    // (along r_ij only) sees. Symmetric in i and j: momentum is conserved.
    const T h = k.kernel.h;
    const T lap = k.hourglass_nu * (me.inv_rho + inv_rho_j) * kv.f * r2 / (r2 + T(0.01) * h * h);
    c.acc -= lap * dv;
  }
  c.L = outer(vol_j * dv, grad);
  c.support = vol_j * kv.w;
  if (kShifting) c.xsph = (vol_j * kv.w) * dv;
  return c;
}

// Sums for the hourglass_stiffness effect (SoilStage with kHg = 2). The SPH velocity gradient does not
// see a checkerboard: neighbouring layers of particles that slide past each other in opposite
// directions strain nothing, so no stress resists them, and under a plate the soil escapes that
// way (results/plate_bin_check, tenth study). Each particle therefore keeps the displacement u that
// its neighbourhood's motion does not explain,
//   du_i/dt = v_i - vbar_i,   vbar_i = sum_n V_n W_in (v_n + L_i (x_i - x_n)) / S_i,   S_i = sum_n V_n W_in,
// over its neighbours n (soil and markers, not itself). Where the kernel is full (sum_n V_n W_in
// (x_i - x_n) = 0) vbar_i = v_i for any linear velocity field, so u stays zero under uniform strain
// and rigid motion; at a free surface, where the SPH gradient L_i falls short, it does not, but
// there the spring's frictional hold (below) is small. A spring of energy
// (m k / 2) |u_i|^2 pulls it back: the force -m k u_i on i, and its reaction m k (V_n W_in / S_i) u_i
// on each neighbour n, which sum to zero (momentum is conserved, and bodies feel their share
// through their markers).
template <typename T>
struct HourglassSums {
  Vec3<T> wv{}, wr{}, react{};  // sum V W v_n, sum V W (x_i - x_n), sum W u_j / S_j (soil neighbours)
  T ws = 0;                     // S_i
  TERRACAL_HD HourglassSums& operator+=(const HourglassSums& o) {
    wv += o.wv;
    wr += o.wr;
    react += o.react;
    ws += o.ws;
    return *this;
  }
};

// Neighbour n's share, from vw = V_n W_in (neighbour_share's kernel support term, so that the GPU,
// which has it at hand, does not evaluate the kernel twice); hg_n is n's SoilArrays::hg record
// (u / S read as u * w), or zero for a marker.
template <typename T>
TERRACAL_HD inline HourglassSums<T> hourglass_share(const SphConstants<T>& k, const Vec3<T>& xi, Vec4<T> pn, Vec4<T> vn, T vw,
                                                     Vec4<T> hg_n) {
  HourglassSums<T> c;
  c.ws = vw;
  c.wv = vw * vn.xyz();
  c.wr = vw * (xi - pn.xyz());
  c.react = (vw * pn.w / k.mass * hg_n.w) * hg_n.xyz();  // W_in u_n / S_n
  return c;
}
// The same where the kernel value is not at hand (the CPU's SIMD sums do not return it per pair).
template <typename T>
TERRACAL_HD inline HourglassSums<T> hourglass_share(const SphConstants<T>& k, const Vec3<T>& xi, Vec4<T> pn, Vec4<T> vn,
                                                     Vec4<T> hg_n) {
  const Vec3<T> r = xi - pn.xyz();
  return hourglass_share(k, xi, pn, vn, k.mass / pn.w * k.kernel.values(std::sqrt(dot(r, r))).w, hg_n);
}

#if !defined(__CUDA_ARCH__)
// The CPU's inner loop. The neighbours listed in `list` (at most kSimdChunk, all within the support;
// room for 8 more) are first copied into structure-of-arrays form, then summed with SIMD across neighbours: x86
// gathers are slow, contiguous loads are not. The arithmetic is neighbour_share's; only the loop
// differs from the GPU's.
constexpr int kSimdChunk = 128;
template <typename T, bool kViscosity, bool kShifting, bool kHourglass>
inline void add_neighbours_simd(SoilSums<T>& sum, const SphConstants<T>& k, const SoilSelf<T>& me,
                                const Vec4<T>* pos, const Vec4<T>* vel, const Vec4<T>* s0, const Vec4<T>* s1,
                                int* list, int n) {
  alignas(64) T px[kSimdChunk + 8], py[kSimdChunk + 8], pz[kSimdChunk + 8], pr[kSimdChunk + 8];
  alignas(64) T vx[kSimdChunk + 8], vy[kSimdChunk + 8], vz[kSimdChunk + 8];
  alignas(64) T sxx[kSimdChunk + 8], syy[kSimdChunk + 8], szz[kSimdChunk + 8], sxy[kSimdChunk + 8],
      sxz[kSimdChunk + 8], syz[kSimdChunk + 8];
  T* const staged[kStagedFields] = {px, py, pz, pr, vx, vy, vz, sxx, syy, szz, sxy, sxz, syz};
  stage_neighbours(pos, vel, s0, s1, list, n, staged);
  T ax = 0, ay = 0, az = 0, dx = 0, dy = 0, dz = 0, sup = 0;
  T l00 = 0, l01 = 0, l02 = 0, l10 = 0, l11 = 0, l12 = 0, l20 = 0, l21 = 0, l22 = 0;
#pragma omp simd reduction(+ : ax, ay, az, dx, dy, dz, sup, l00, l01, l02, l10, l11, l12, l20, l21, l22)
  for (int q = 0; q < n; ++q) {
    const SoilSums<T> c = neighbour_share<T, kViscosity, kShifting, kHourglass>(
        k, me, Vec4<T>{px[q], py[q], pz[q], pr[q]}, Vec4<T>{vx[q], vy[q], vz[q], T(0)},
        Vec4<T>{sxx[q], syy[q], szz[q], sxy[q]}, Vec4<T>{sxz[q], syz[q], T(0), T(0)});
    ax += c.acc.x; ay += c.acc.y; az += c.acc.z;
    dx += c.xsph.x; dy += c.xsph.y; dz += c.xsph.z;
    sup += c.support;
    l00 += c.L.m[0][0]; l01 += c.L.m[0][1]; l02 += c.L.m[0][2];
    l10 += c.L.m[1][0]; l11 += c.L.m[1][1]; l12 += c.L.m[1][2];
    l20 += c.L.m[2][0]; l21 += c.L.m[2][1]; l22 += c.L.m[2][2];
  }
  sum.acc += Vec3<T>{ax, ay, az};
  sum.xsph += Vec3<T>{dx, dy, dz};
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

// MarkerVelocity::kMirrorContact: a soil particle whose centre is further than this many spacings
// from the wall's surface is not in contact (one in contact sits half a spacing from it).
constexpr double kContactFade = 0.65;

// Boundary markers (Adami et al. 2012): stress (and, optionally, velocity) extrapolated from the soil around each
// marker, then the force of the soil on the marker, which the host sums into body wrenches.
template <typename T, bool kViscosity>
struct MarkerStage {
  SphConstants<T> k;
  GridGeometry<T> grid;
  const int* soil_begin;
  SoilArrays<T> soil;  // the state the stage is evaluated at
  MarkerArrays<T> mk;
  const BodyPose<T>* poses;  // to turn the wall normals of MarkerVelocity::kMirrorImage into the world frame

  TERRACAL_HD void operator()(long m) const {
    const Vec4<T> pm = mk.pos[m];
    const Vec3<T> xm = pm.xyz();
    const Vec4<T> wv = mk.wall_vel[m];
    const T support2 = k.kernel.support2();
    // visit(f) calls f(j) for every soil particle j within the support of the marker, twice per
    // marker (extrapolation, then force).
#if defined(__CUDA_ARCH__)
    auto visit = [&](auto&& f) {
      grid.for_each_neighbour_range(xm, soil_begin,
                                    [&](int first, int last) { for_each_hit(soil.pos, first, last, -1, xm, support2, f); });
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
      const T dist = std::sqrt(dot(r, r));
      if (contact_rule && dist - depth < gap) gap = dist - depth;
      const T w = k.kernel.values(dist).w;
      sum_w += w;
      sum_s = sum_s + w * stress_of(soil.s0[j], soil.s1[j]);
      sum_v += w * soil.vel[j].xyz();
      sum_rho_r += (w * pj.w) * r;
    });
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
    mk.vel[m] = make_vec4(vm, T(0));
    mk.s0[m] = {sm.xx, sm.yy, sm.zz, sm.xy};
    mk.s1[m] = {sm.xz, sm.yz, T(0), sum_w};

    // Force of the soil on the marker: minus what the marker does to each soil particle; with
    // hourglass_stiffness also the reaction of the soil particles' springs on the marker,
    // m k V_m sum_j W u_j / S_j (see HourglassSums), from the same kernel value.
    const bool stiff = k.hourglass_k > T(0);
    Vec3<T> f{}, react{};
    visit([&](int j) {
      const Vec4<T> pj = soil.pos[j];
      const Vec3<T> r = pj.xyz() - xm;  // from the soil particle's side: r_jm
      const T r2 = dot(r, r);
      const typename SphKernel<T>::Values kv = k.kernel.values(std::sqrt(r2));
      const T rho_j = pj.w;
      f -= pair_acceleration<T, kViscosity>(k, stress_of(soil.s0[j], soil.s1[j]), T(1) / (rho_j * rho_j), rho_j,
                                            soil.vel[j].xyz(), sm, inv_rho2_m, rho_m, vm, r, r2, kv.f * r);
      if (stiff) {
        const Vec4<T> g = soil.hg[j];
        react += (kv.w * g.w) * g.xyz();
      }
    });
    if (stiff) f += (k.hourglass_k / rho_m) * react;
    mk.force[m] = make_vec4((k.mass * k.mass) * f, T(0));
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
  // The marker's wall normal in the world frame, w = its depth (0: none).
  TERRACAL_HD Vec4<T> world_normal(long m) const {
    const Vec4<T> nl = mk.normal[m];
    if (!(nl.w > T(0))) return Vec4<T>{};
    const BodyPose<T>& b = poses[int(mk.local[m].w)];
    return {b.R[0] * nl.x + b.R[1] * nl.y + b.R[2] * nl.z, b.R[3] * nl.x + b.R[4] * nl.y + b.R[5] * nl.z,
            b.R[6] * nl.x + b.R[7] * nl.y + b.R[8] * nl.z, nl.w};
  }

  TERRACAL_HD Vec3<T> mirror_image_velocity(long m, const Vec3<T>& xm, const Vec3<T>& v_wall, const Vec3<T>& adami) const {
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

// One stage for one soil particle: accumulate the momentum balance, the velocity gradient and
// the kernel support over soil and marker neighbours, then integrate and return-map the stress.
// kHg: 0 no hourglass effect, 1 hourglass_damping, 2 hourglass_stiffness (with the damping term,
// whose viscosity is zero unless hourglass_damping is named too).
template <typename T, bool kViscosity, bool kShifting, int kHg>
struct SoilStage {
  static constexpr bool kHourglass = kHg >= 1;
  static constexpr bool kStiff = kHg == 2;
  SphConstants<T> k;
  GridGeometry<T> grid;
  const int* soil_begin;
  const int* marker_begin;
  SoilArrays<T> eval, base, out;
  MarkerArrays<T> mk;
  T dt;

  TERRACAL_HD void operator()(long i) const {
    const Vec4<T> vb = base.vel[i];
    if (vb.w != T(kParticleActive)) {  // frozen (outside the active domain) or lost: carried unchanged
      if (base.pos != out.pos) {
        out.pos[i] = base.pos[i];
        out.vel[i] = vb;
        out.s0[i] = base.s0[i];
        out.s1[i] = base.s1[i];
        if (kStiff) out.hg[i] = base.hg[i];
      }
      return;
    }
    const Vec4<T> pi4 = eval.pos[i];
    SoilSelf<T> me;
    me.x = pi4.xyz();
    me.v = eval.vel[i].xyz();
    me.rho = pi4.w;
    me.inv_rho2 = T(1) / (me.rho * me.rho);
    me.inv_rho = kHourglass ? T(1) / me.rho : T(0);  // only the hourglass damping needs it
    me.s = stress_of(eval.s0[i], eval.s1[i]);
    const T support2 = k.kernel.support2();

    SoilSums<T> sum;
    sum.support = k.mass / me.rho * k.kernel.values(T(0)).w;
    HourglassSums<T> hs;
#if defined(__CUDA_ARCH__)
    // GPU: one thread per particle walks its neighbour rows, testing a row before summing its hits.
    grid.for_each_neighbour_range(me.x, soil_begin, [&](int first, int last) {
      for_each_hit(eval.pos, first, last, int(i), me.x, support2, [&](int j) {
        const Vec4<T> pj = load(eval.pos + j), vj = load(eval.vel + j);
        const SoilSums<T> c =
            neighbour_share<T, kViscosity, kShifting, kHourglass>(k, me, pj, vj, load(eval.s0 + j), load(eval.s1 + j));
        sum += c;
        if constexpr (kStiff) hs += hourglass_share(k, me.x, pj, vj, c.support, load(eval.hg + j));
      });
    });
    grid.for_each_neighbour_range(me.x, marker_begin, [&](int first, int last) {
      for_each_hit(mk.pos, first, last, -1, me.x, support2, [&](int j) {
        const Vec4<T> pj = load(mk.pos + j), vj = load(mk.vel + j);
        const SoilSums<T> c = neighbour_share<T, kViscosity, kShifting, false>(k, me, pj, vj, load(mk.s0 + j), load(mk.s1 + j));
        sum += c;
        if constexpr (kStiff) hs += hourglass_share(k, me.x, pj, vj, c.support, Vec4<T>{});
      });
    });
#else
    // CPU: list the neighbours within the support (branch-free), then sum them with SIMD. The list
    // is flushed whenever it fills, so any number of neighbours is handled.
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
      add_neighbours_simd<T, kViscosity, kShifting, kHourglass>(sum, k, me, eval.pos, eval.vel, eval.s0, eval.s1, list, n);
      if constexpr (kStiff)
        for (int q = 0; q < n; ++q) hs += hourglass_share(k, me.x, eval.pos[list[q]], eval.vel[list[q]], eval.hg[list[q]]);
    };
    grid.for_each_neighbour_range(me.x, soil_begin, [&](int first, int last) { collect(eval.pos, first, last, i, flush_soil); });
    flush_soil();
    n = 0;
    auto flush_markers = [&] {
      add_neighbours_simd<T, kViscosity, kShifting, false>(sum, k, me, mk.pos, mk.vel, mk.s0, mk.s1, list, n);
      if constexpr (kStiff)
        for (int q = 0; q < n; ++q) hs += hourglass_share(k, me.x, mk.pos[list[q]], mk.vel[list[q]], Vec4<T>{});
    };
    grid.for_each_neighbour_range(me.x, marker_begin, [&](int first, int last) { collect(mk.pos, first, last, -1, flush_markers); });
    flush_markers();
#endif
    const Mat3<T>& L = sum.L;
    Vec3<T> acc = k.mass * sum.acc + k.gravity;
    Vec4<T> hg_new{};
    if constexpr (kStiff) {
      const Vec4<T> hg_e = eval.hg[i];
      acc += k.hourglass_k * ((k.mass / me.rho) * hs.react - hg_e.xyz());
      if (sum.support >= k.free_surface_support && hs.ws > T(0)) {
        // A free-surface particle (as below for the stress) keeps no hourglass displacement.
        const T inv_s = T(1) / hs.ws;
        const Vec3<T> vbar = inv_s * (hs.wv + L * hs.wr);
        Vec3<T> u = base.hg[i].xyz() + dt * (me.v - vbar);
        // The spring is frictional, like the soil: it holds at most the force that the particle's
        // confinement gives a grain, (mu_s p + c) / (rho d0) per unit mass. Loose grains at the
        // surface are not held in place, and an error of the velocity extrapolation that keeps
        // feeding u (at a wall's corner) cannot build up a force that throws a particle out.
        T p = -me.s.trace() / T(3);
        p = p > T(0) ? p : T(0);
        const T u_max = (k.model.mu_s * p + k.model.cohesion) / (me.rho * k.spacing * k.hourglass_k);
        const T u2 = dot(u, u);
        if (u2 > u_max * u_max) u = (u_max / std::sqrt(u2)) * u;
        hg_new = make_vec4(u, inv_s);
      }
    }
    const T div_v = L.m[0][0] + L.m[1][1] + L.m[2][2];
    const Sym3<T> rate = jaumann_rate(me.s, L, k.model);

    const Vec4<T> pb = base.pos[i];
    const Vec4<T> s0b = base.s0[i], s1b = base.s1[i];
    Vec3<T> drift = me.v;
    if (kShifting) drift += k.xsph * sum.xsph;
    const Vec3<T> x_new = pb.xyz() + dt * drift;
    T rho_new = pb.w - dt * me.rho * div_v;
    const Vec3<T> v_new = vb.xyz() + dt * acc;
    Sym3<T> s_new = stress_of(s0b, s1b) + dt * rate;
    T plastic = s1b.z + return_map(s_new, shear_rate(L), k.model);
    // A particle with a truncated kernel (free surface) cannot resolve its velocity gradient;
    // it carries no stress rather than a spurious one.
    if (sum.support < k.free_surface_support) s_new = Sym3<T>{};
    // Soil does not compress to half its volume. A density above 1.5 rho0 is the spurious
    // divergence of a particle squeezed against a wall, which would otherwise grow without bound
    // and make the walls' hydrostatic head (proportional to it) throw the particle about.
    const T rho_cap = T(1.5) * k.model.rho0;
    if (rho_new > rho_cap) rho_new = rho_cap;
    out.pos[i] = make_vec4(x_new, rho_new);
    out.vel[i] = make_vec4(v_new, T(kParticleActive));
    out.s0[i] = {s_new.xx, s_new.yy, s_new.zz, s_new.xy};
    out.s1[i] = {s_new.xz, s_new.yz, plastic, sum.support};
    if constexpr (kStiff) out.hg[i] = hg_new;
  }
};

// Rigid motion of body markers (BodyPose): x = c + R local, v_wall = v + omega x (R local).
template <typename T>
struct MarkerPoseUpdate {
  const BodyPose<T>* poses;
  MarkerArrays<T> mk;
  TERRACAL_HD void operator()(long m) const {
    const Vec4<T> l = mk.local[m];
    const BodyPose<T>& b = poses[int(l.w)];
    if (!b.moving) return;
    const Vec3<T> rl{b.R[0] * l.x + b.R[1] * l.y + b.R[2] * l.z, b.R[3] * l.x + b.R[4] * l.y + b.R[5] * l.z,
                     b.R[6] * l.x + b.R[7] * l.y + b.R[8] * l.z};
    const Vec4<T> p = mk.pos[m];
    mk.pos[m] = make_vec4(b.center + rl, p.w);
    mk.wall_vel[m] = make_vec4(b.velocity + cross(b.omega, rl), T(1));
  }
};

// Cell keys for sorting; a soil particle that has left the domain, or broken into the walls (left
// the room [room_lo, room_hi]), is marked lost, stopped and parked in the last bin, where no
// neighbour loop sees it.
template <typename T>
struct SoilCellKey {
  GridGeometry<T> grid;
  SoilArrays<T> s;
  Vec3<T> room_lo, room_hi;
  int* keys;
  int* values;
  TERRACAL_HD void operator()(long i) const {
    const Vec3<T> x = s.pos[i].xyz();
    int key = grid.key(x);
    const bool in_room = x.x >= room_lo.x && x.y >= room_lo.y && x.z >= room_lo.z && x.x <= room_hi.x &&
                         x.y <= room_hi.y && x.z <= room_hi.z;
    if (!in_room) key = grid.cells();
    if (s.vel[i].w == T(kParticleLost)) key = grid.cells();
    if (key == grid.cells() && s.vel[i].w != T(kParticleLost)) s.vel[i] = {T(0), T(0), T(0), T(kParticleLost)};
    keys[i] = key;
    values[i] = int(i);
  }
};

template <typename T>
struct MarkerCellKey {
  GridGeometry<T> grid;
  MarkerArrays<T> mk;
  int* keys;
  int* values;
  TERRACAL_HD void operator()(long i) const {
    keys[i] = grid.key(mk.pos[i].xyz());
    values[i] = int(i);
  }
};

// Gathers a record array into sorted order: dst[i] = src[perm[i]].
template <typename R>
struct Gather {
  const R* src;
  R* dst;
  const int* perm;
  TERRACAL_HD void operator()(long i) const { dst[i] = src[perm[i]]; }
};

// Active domain: particles outside every box (moving bodies' bounds plus a margin) are frozen.
template <typename T>
struct MarkActive {
  const ActiveBox<T>* boxes;
  int count;
  SoilArrays<T> s;
  TERRACAL_HD void operator()(long i) const {
    const Vec4<T> v = s.vel[i];
    if (v.w == T(kParticleLost)) return;
    const Vec3<T> x = s.pos[i].xyz();
    bool active = false;
    for (int b = 0; b < count && !active; ++b)
      active = x.x >= boxes[b].lo.x && x.x <= boxes[b].hi.x && x.y >= boxes[b].lo.y && x.y <= boxes[b].hi.y &&
               x.z >= boxes[b].lo.z && x.z <= boxes[b].hi.z;
    const T status = active ? T(kParticleActive) : T(kParticleFrozen);
    if (v.w != status) s.vel[i] = {active ? v.x : T(0), active ? v.y : T(0), active ? v.z : T(0), status};
  }
};

}  // namespace terracal
