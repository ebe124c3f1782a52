#pragma once
// The per-particle physics of one Runge-Kutta stage, written once for both backends
// (DESIGN.md §4). Each functor is called as f(i) by parallel_for on the CPU or in a CUDA kernel.
//
// A stage evaluates the rates at the `eval` state and writes out = base + dt * rate. The midpoint
// step is stage(A -> B, dt/2) followed by stage(B -> A, dt): the second stage reads B and updates
// A in place, which is safe because a particle reads only its own record of A.
#include "highfi/sph_fields.hpp"

namespace terracal {

// The acceleration that particle i receives from neighbour j per unit neighbour mass:
// (sigma_i/rho_i^2 + sigma_j/rho_j^2) . grad_i W_ij  -  Pi_ij grad_i W_ij  (Monaghan viscosity).
// Used by the soil pass and, with the roles of soil and marker fixed, by the marker force pass, so
// that the forces on bodies are exactly the reaction of those on the soil.
template <typename T, bool kViscosity>
TERRACAL_HD inline Vec3<T> pair_acceleration(const SphConstants<T>& k, const Sym3<T>& si, T inv_rho2_i, T rho_i,
                                             const Vec3<T>& vi, const Sym3<T>& sj, T rho_j, const Vec3<T>& vj,
                                             const Vec3<T>& rij, T r2, const Vec3<T>& grad) {
  const T inv_rho2_j = T(1) / (rho_j * rho_j);
  const Sym3<T> a = inv_rho2_i * si + inv_rho2_j * sj;
  Vec3<T> acc = a * grad;
  if (kViscosity) {
    const T vr = dot(vi - vj, rij);
    if (vr < T(0)) {
      const T h = k.kernel.h;
      const T mu = h * vr / (r2 + T(0.01) * h * h);
      const T pi = -k.viscosity_alpha * k.sound_speed * mu * T(2) / (rho_i + rho_j);
      acc -= pi * grad;
    }
  }
  return acc;
}

// Boundary markers (Adami et al. 2012): stress and velocity extrapolated from the soil around each
// marker, then the force of the soil on the marker, which the host sums into body wrenches.
template <typename T, bool kViscosity>
struct MarkerStage {
  SphConstants<T> k;
  GridGeometry<T> grid;
  const int* soil_begin;
  SoilArrays<T> soil;  // the state the stage is evaluated at
  MarkerArrays<T> mk;

  TERRACAL_HD void operator()(long m) const {
    const Vec4<T> pm = mk.pos[m];
    const Vec3<T> xm = pm.xyz();
    const Vec4<T> wv = mk.wall_vel[m];
    T sum_w = 0;
    Sym3<T> sum_s{};
    Vec3<T> sum_v{}, sum_rho_r{};
    const T support2 = k.kernel.support2();
    grid.for_each_neighbour_range(xm, soil_begin, [&](int first, int last) {
      for (int j = first; j < last; ++j) {
        const Vec4<T> pj = soil.pos[j];
        const Vec3<T> r = xm - pj.xyz();
        const T r2 = dot(r, r);
        if (r2 >= support2) continue;
        const T w = k.kernel.w(std::sqrt(r2));
        sum_w += w;
        sum_s = sum_s + w * stress_of(soil.s0[j], soil.s1[j]);
        const Vec4<T> vj = soil.vel[j];
        sum_v += w * vj.xyz();
        sum_rho_r += (w * pj.w) * r;
      }
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
      vm = T(2) * wv.xyz() - inv * sum_v;
    }
    const T rho_m = pm.w;
    mk.vel[m] = make_vec4(vm, T(0));
    mk.s0[m] = {sm.xx, sm.yy, sm.zz, sm.xy};
    mk.s1[m] = {sm.xz, sm.yz, T(0), sum_w};

    // Force of the soil on the marker: minus what the marker does to each soil particle.
    Vec3<T> f{};
    grid.for_each_neighbour_range(xm, soil_begin, [&](int first, int last) {
      for (int j = first; j < last; ++j) {
        const Vec4<T> pj = soil.pos[j];
        const Vec3<T> r = pj.xyz() - xm;  // from the soil particle's side: r_jm
        const T r2 = dot(r, r);
        if (r2 >= support2) continue;
        const Vec3<T> grad = k.kernel.grad_factor(std::sqrt(r2)) * r;
        const T rho_j = pj.w;
        const Vec3<T> a = pair_acceleration<T, kViscosity>(k, stress_of(soil.s0[j], soil.s1[j]), T(1) / (rho_j * rho_j),
                                                            rho_j, soil.vel[j].xyz(), sm, rho_m, vm, r, r2, grad);
        f -= a;
      }
    });
    mk.force[m] = make_vec4((k.mass * k.mass) * f, T(0));
  }
};

// One stage for one soil particle: accumulate the momentum balance, the velocity gradient and
// the kernel support over soil and marker neighbours, then integrate and return-map the stress.
template <typename T, bool kViscosity, bool kShifting>
struct SoilStage {
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
      }
      return;
    }
    const Vec4<T> pi4 = eval.pos[i], vi4 = eval.vel[i];
    const Vec3<T> xi = pi4.xyz(), vi = vi4.xyz();
    const T rho_i = pi4.w, inv_rho2_i = T(1) / (rho_i * rho_i);
    const Sym3<T> si = stress_of(eval.s0[i], eval.s1[i]);
    const T support2 = k.kernel.support2();

    Vec3<T> acc{}, xsph{};
    Mat3<T> L{};
    T support = k.mass / rho_i * k.kernel.w(T(0));

    auto interact = [&](const Vec3<T>& xj, T rho_j, const Vec3<T>& vj, const Sym3<T>& sj, T r2, const Vec3<T>& r) {
      const T rr = std::sqrt(r2);
      const Vec3<T> grad = k.kernel.grad_factor(rr) * r;
      acc += pair_acceleration<T, kViscosity>(k, si, inv_rho2_i, rho_i, vi, sj, rho_j, vj, r, r2, grad);
      const T vol_j = k.mass / rho_j;
      const Vec3<T> dv = vj - vi;
      add_outer(L, vol_j * dv, grad);
      const T w = k.kernel.w(rr);
      support += vol_j * w;
      if (kShifting) xsph += (vol_j * w) * dv;
      (void)xj;
    };
    grid.for_each_neighbour_range(xi, soil_begin, [&](int first, int last) {
      for (int j = first; j < last; ++j) {
        const Vec4<T> pj = load(eval.pos + j);
        const Vec3<T> r = xi - pj.xyz();
        const T r2 = dot(r, r);
        if (r2 >= support2 || j == int(i)) continue;
        interact(pj.xyz(), pj.w, load(eval.vel + j).xyz(), stress_of(load(eval.s0 + j), load(eval.s1 + j)), r2, r);
      }
    });
    grid.for_each_neighbour_range(xi, marker_begin, [&](int first, int last) {
      for (int j = first; j < last; ++j) {
        const Vec4<T> pj = load(mk.pos + j);
        const Vec3<T> r = xi - pj.xyz();
        const T r2 = dot(r, r);
        if (r2 >= support2) continue;
        interact(pj.xyz(), pj.w, load(mk.vel + j).xyz(), stress_of(load(mk.s0 + j), load(mk.s1 + j)), r2, r);
      }
    });
    acc = k.mass * acc + k.gravity;

    const T div_v = L.m[0][0] + L.m[1][1] + L.m[2][2];
    const Sym3<T> rate = jaumann_rate(si, L, k.model);

    const Vec4<T> pb = base.pos[i];
    const Vec4<T> s0b = base.s0[i], s1b = base.s1[i];
    Vec3<T> drift = vi;
    if (kShifting) drift += k.xsph * xsph;
    const Vec3<T> x_new = pb.xyz() + dt * drift;
    const T rho_new = pb.w - dt * rho_i * div_v;
    const Vec3<T> v_new = vb.xyz() + dt * acc;
    Sym3<T> s_new = stress_of(s0b, s1b) + dt * rate;
    T plastic = s1b.z + return_map(s_new, shear_rate(L), k.model);
    // A particle with a truncated kernel (free surface) cannot resolve its velocity gradient;
    // it carries no stress rather than a spurious one.
    if (support < k.free_surface_support) s_new = Sym3<T>{};
    out.pos[i] = make_vec4(x_new, rho_new);
    out.vel[i] = make_vec4(v_new, T(kParticleActive));
    out.s0[i] = {s_new.xx, s_new.yy, s_new.zz, s_new.xy};
    out.s1[i] = {s_new.xz, s_new.yz, plastic, support};
  }
};

// Rigid motion of body markers: x = c + R local, v_wall = v + omega x (R local).
template <typename T>
struct BodyPose {
  Vec3<T> center{}, velocity{}, omega{};
  T R[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  int moving = 0;
};

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

// Cell keys for sorting; a soil particle that has left the domain is marked lost, stopped and
// parked in the last bin, where no neighbour loop sees it.
template <typename T>
struct SoilCellKey {
  GridGeometry<T> grid;
  SoilArrays<T> s;
  int* keys;
  int* values;
  TERRACAL_HD void operator()(long i) const {
    int key = grid.key(s.pos[i].xyz());
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
struct ActiveBox {
  Vec3<T> lo{}, hi{};
};
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
