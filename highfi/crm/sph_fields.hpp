#pragma once
// Storage and constants shared by both backends: boundary markers as a structure of arrays of
// 16-byte Vec4 records (so that a neighbour's field is one 128-bit load on the GPU; the soil's
// arrays, which also hold the effects' records, are in soil_arrays.hpp), the neighbour grid, and
// the physical constants of the core. Pointers are device pointers on the CUDA backend and host
// pointers on the CPU one; the physics never knows which.
#include "core/host_device.hpp"
#include "core/lane_group.hpp"
#include "core/vec.hpp"
#include "highfi/crm/marker_velocity.hpp"
#include "highfi/crm/soil_model.hpp"
#include "highfi/crm/sph_kernel.hpp"

namespace terracal {

// Status of a soil particle, kept in vel.w.
enum ParticleStatus : int { kParticleActive = 0, kParticleFrozen = 1, kParticleLost = 2 };

template <typename T>
struct MarkerArrays {
  Vec4<T>* pos = nullptr;  // x, y, z, density seen by the soil
  Vec4<T>* vel = nullptr;  // velocity seen by the soil: 2 v_wall - extrapolated v (Adami 2012)
  Vec4<T>* s0 = nullptr;   // extrapolated stress, as SoilArrays
  Vec4<T>* s1 = nullptr;
  Vec4<T>* local = nullptr;     // position in the body frame; w = body index
  Vec4<T>* wall_vel = nullptr;  // rigid-body velocity at the marker; w = 1 when the body moves
  Vec4<T>* force = nullptr;     // force of the soil on the marker (x, y, z)
  Vec4<T>* normal = nullptr;    // body frame: unit normal from the marker towards the soil; w = depth (0: none)
};

// A neighbour's record, through the GPU's read-only data cache (valid: a stage never writes the
// state it reads neighbours from).
template <typename T>
TERRACAL_HD inline Vec4<T> load(const Vec4<T>* p) {
#if defined(__CUDA_ARCH__)
  if constexpr (sizeof(T) == 4) {
    const float4 v = __ldg(reinterpret_cast<const float4*>(p));
    return {v.x, v.y, v.z, v.w};
  }
#endif
  return *p;
}

template <typename T>
TERRACAL_HD inline Sym3<T> stress_of(const Vec4<T>& s0, const Vec4<T>& s1) {
  return {s0.x, s0.y, s0.z, s0.w, s1.x, s1.y};
}

// Uniform grid of cell size >= 2h / reach over the domain; cells ordered x fastest, so the cells of
// a row of neighbours are contiguous in the sorted arrays. Key `cells()` is the bin for particles
// outside the domain (lost), which no neighbour loop visits. reach = 1 is the plain 2h grid
// (27 cells, ~13.8 particles each at h = 1.2 d0); reach = 2 uses cells of h (125 cells of ~1.7),
// which checks ~40 % fewer candidates for the same neighbours.
template <typename T>
struct GridGeometry {
  Vec3<T> origin{};
  T inv_cell = 1;
  int nx = 1, ny = 1, nz = 1;
  int reach = 1;
  TERRACAL_HD int cells() const { return nx * ny * nz; }
  TERRACAL_HD bool cell_coords(const Vec3<T>& p, int& ix, int& iy, int& iz) const {
    const T fx = (p.x - origin.x) * inv_cell, fy = (p.y - origin.y) * inv_cell, fz = (p.z - origin.z) * inv_cell;
    // The comparisons are written so that NaN also counts as outside.
    if (!(fx >= T(0) && fy >= T(0) && fz >= T(0) && fx < T(nx) && fy < T(ny) && fz < T(nz))) return false;
    ix = int(fx);
    iy = int(fy);
    iz = int(fz);
    if (ix >= nx) ix = nx - 1;
    if (iy >= ny) iy = ny - 1;
    if (iz >= nz) iz = nz - 1;
    return true;
  }
  TERRACAL_HD int key(const Vec3<T>& p) const {
    int ix, iy, iz;
    if (!cell_coords(p, ix, iy, iz)) return cells();
    return ix + nx * (iy + ny * iz);
  }
  // Calls f(first, last) for the contiguous index ranges (one per row) that cover the cells within
  // `reach` of the cell of p.
  template <typename F>
  TERRACAL_HD void for_each_neighbour_range(const Vec3<T>& p, const int* begin, const SingleLane&, F&& f) const {
    for_each_neighbour_range(p, begin, f);
  }
  template <typename F>
  TERRACAL_HD void for_each_neighbour_range(const Vec3<T>& p, const int* begin, F&& f) const {
    int ix, iy, iz;
    if (!cell_coords(p, ix, iy, iz)) return;
    const int x0 = ix - reach > 0 ? ix - reach : 0, x1 = ix + reach < nx ? ix + reach : nx - 1;
    for (int z = iz - reach; z <= iz + reach; ++z) {
      if (z < 0 || z >= nz) continue;
      for (int y = iy - reach; y <= iy + reach; ++y) {
        if (y < 0 || y >= ny) continue;
        const int row = nx * (y + ny * z);
        f(begin[row + x0], begin[row + x1 + 1]);
      }
    }
  }
  // The same for lane g.lane of a group: rows g.lane, g.lane + g.lanes, ... of the (2 reach + 1)^2
  // block (z major), so that the group's lanes take their k-th rows in the same iteration and run
  // side by side instead of one after another.
  template <typename F>
  TERRACAL_HD void for_each_neighbour_range(const Vec3<T>& p, const int* begin, const LaneGroup& g, F&& f) const {
    int ix, iy, iz;
    if (!cell_coords(p, ix, iy, iz)) return;
    const int x0 = ix - reach > 0 ? ix - reach : 0, x1 = ix + reach < nx ? ix + reach : nx - 1;
    const int side = 2 * reach + 1;
    for (int r = g.lane; r < side * side; r += g.lanes) {
      const int z = iz - reach + r / side, y = iy - reach + r % side;
      if (z < 0 || z >= nz || y < 0 || y >= ny) continue;
      const int row = nx * (y + ny * z);
      f(begin[row + x0], begin[row + x1 + 1]);
    }
  }
};

// Everything the core physics needs besides the particles, in the precision of the particle state
// (the effects' constants are beside it: CrmEffectConstants, effects/crm_effects.hpp).
template <typename T>
struct SphConstants {
  SphKernel<T> kernel;
  SoilModel<T> model;
  T mass = 0;  // particle mass rho0 d0^3 (soil and markers alike)
  Vec3<T> gravity{};
  T free_surface_support = 0;  // kernel support (Shepard sum) below which a particle is on the free surface
  T spacing = 0;               // d0
  MarkerVelocity marker_velocity = MarkerVelocity::kMirror;  // CrmNumerics::marker_velocity
  T wall_contact = 0;            // the walls' contact pressure in units of the soil's (wall_contact.hpp)
  T wall_contact_inv_reach = 0;  // 1 / d0
};

// A body's pose and rigid motion, as the marker update reads it.
template <typename T>
struct BodyPose {
  Vec3<T> center{}, velocity{}, omega{};
  T R[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  int moving = 0;
};

// Adds marker m's force and its torque about `center` to acc = (force, torque), in double: the body
// wrench both backends sum (the CPU in marker order, the GPU in per-thread shares).
template <typename T>
TERRACAL_HD inline void add_marker_wrench(const MarkerArrays<T>& mk, long m, const Vec3<double>& center, double* acc) {
  const Vec4<T> f4 = mk.force[m], x4 = mk.pos[m];
  const Vec3<double> f{double(f4.x), double(f4.y), double(f4.z)};
  const Vec3<double> t = cross(Vec3<double>{double(x4.x), double(x4.y), double(x4.z)} - center, f);
  acc[0] += f.x;
  acc[1] += f.y;
  acc[2] += f.z;
  acc[3] += t.x;
  acc[4] += t.y;
  acc[5] += t.z;
}

// Active domain: a box around a moving body plus a margin; soil outside every box is frozen.
template <typename T>
struct ActiveBox {
  Vec3<T> lo{}, hi{};
  // Whether x lies within distance `reach` of the box (per axis).
  TERRACAL_HD bool near(const Vec3<T>& x, T reach) const {
    return x.x >= lo.x - reach && x.x <= hi.x + reach && x.y >= lo.y - reach && x.y <= hi.y + reach &&
           x.z >= lo.z - reach && x.z <= hi.z + reach;
  }
};

// Whether a marker at x can be a neighbour of an active particle: within the kernel's support of
// one of the active domain's boxes. count 0: no active domain, every marker counts.
template <typename T>
TERRACAL_HD inline bool near_active(const ActiveBox<T>* boxes, int count, const Vec3<T>& x, T support) {
  if (count == 0) return true;
  for (int b = 0; b < count; ++b)
    if (boxes[b].near(x, support)) return true;
  return false;
}

}  // namespace terracal
