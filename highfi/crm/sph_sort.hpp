#pragma once
// The per-step bookkeeping around the two stages, written once for both backends: the markers'
// rigid motion, the cell keys the particles are sorted by, the gathers into sorted order, and the
// active domain's marks.
#include "core/lane_group.hpp"
#include "highfi/crm/soil_arrays.hpp"

namespace terracal {

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
// The same over a list of markers.
template <typename T>
struct ListedMarkerPoseUpdate {
  MarkerPoseUpdate<T> update;
  const int* list;
  TERRACAL_HD void operator()(long j) const { update(list[j]); }
};

// Entries of a sorted run of n indices that are less than i.
TERRACAL_HD inline int count_less(const int* run, int n, int i) {
  int lo = 0, hi = n;
  while (lo < hi) {
    const int mid = (lo + hi) >> 1;
    if (run[mid] < i)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo;
}

// The keys of a sorted run, stored.
struct StoredKeys {
  const int* keys;
  TERRACAL_HD int operator()(int q) const { return keys[q]; }
};

// Entries of a run of n sorted by (key, index) that come before (key, i); key_of(q) is entry q's key.
template <typename KeyOf>
TERRACAL_HD int count_pairs_before(const KeyOf& key_of, const int* index, int n, int key, int i) {
  int lo = 0, hi = n;
  while (lo < hi) {
    const int mid = (lo + hi) >> 1;
    const int k = key_of(mid);
    if (k < key || (k == key && index[mid] < i))
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo;
}

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

// Cell keys of a subset of the markers, by canonical index: keys[j] and values[j] = list[j] for the
// marker list[j]. With the list in ascending order, a stable sort by key orders them by (cell, index),
// as the full sort orders every marker.
template <typename T>
struct MarkerSubsetCellKey {
  GridGeometry<T> grid;
  const Vec4<T>* pos;  // canonical positions
  const int* list;
  int* keys;
  int* values;
  TERRACAL_HD void operator()(long j) const {
    const int m = list[j];
    keys[j] = grid.key(pos[m].xyz());
    values[j] = m;
  }
};

// The markers' sorted order from two runs, each sorted by (cell, canonical index): the markers that
// never move (walls and bodies at rest: sorted once, their keys worked out again from their fixed
// positions instead of stored) and the moving bodies' markers (sorted at every pose). Each marker's
// place is its place in its own run plus the number of the other run's markers that come before it,
// so the result is the stable sort of all markers by cell, to the last index, at the cost of sorting
// only the moving ones.
template <typename T>
struct MergeMarkerRuns {
  GridGeometry<T> grid;
  const Vec4<T>* pos;  // canonical positions
  const int* fixed;    // the fixed run's canonical indices
  int n_fixed;
  const int* moving_keys;
  const int* moving_index;
  int n_moving;
  int* keys;  // out: every marker's cell, in sorted order
  int* perm;  // out: the canonical index at each sorted place

  // The fixed run's keys, worked out from the fixed positions.
  struct FixedKeys {
    GridGeometry<T> grid;
    const Vec4<T>* pos;
    const int* fixed;
    TERRACAL_HD int operator()(int q) const { return grid.key(pos[fixed[q]].xyz()); }
  };
  TERRACAL_HD void operator()(long i) const {
    const FixedKeys fixed_keys{grid, pos, fixed};
    int key, m, place;
    if (i < n_fixed) {
      key = fixed_keys(int(i));
      m = fixed[i];
      // Most fixed markers (the walls) lie in cells before or after every moving one.
      if (n_moving == 0 || key < moving_keys[0])
        place = int(i);
      else if (key > moving_keys[n_moving - 1])
        place = int(i) + n_moving;
      else
        place = int(i) + count_pairs_before(StoredKeys{moving_keys}, moving_index, n_moving, key, m);
    } else {
      const int j = int(i - n_fixed);
      key = moving_keys[j];
      m = moving_index[j];
      place = j + count_pairs_before(fixed_keys, fixed, n_fixed, key, m);
    }
    keys[place] = key;
    perm[place] = m;
  }
};

// begin[c] = the first sorted index whose key is c or more (a binary search per cell).
struct CellBegin {
  const int* keys;
  int n;
  int* begin;
  TERRACAL_HD void operator()(long c) const { begin[c] = count_less(keys, n, int(c)); }
};

// Gathers a record array into sorted order: dst[i] = src[perm[i]].
template <typename R>
struct Gather {
  const R* src;
  R* dst;
  const int* perm;
  TERRACAL_HD void operator()(long i) const { dst[i] = src[perm[i]]; }
};

// Gathers a soil state but its positions (gathered first: their memory then holds perm) and the
// ids into sorted order, in one pass (one launch instead of one per array).
template <typename T>
struct GatherSoil {
  SoilArrays<T> src, dst;
  const int* ids_src;
  int* ids_dst;
  const int* perm;
  TERRACAL_HD void operator()(long i) const {
    const int p = perm[i];
    dst.vel[i] = src.vel[p];
    dst.s0[i] = src.s0[p];
    dst.s1[i] = src.s1[p];
    for (int r = 0; r < kCrmRecordSlots; ++r)
      if (src.record[r]) dst.record[r][i] = src.record[r][p];
    ids_dst[i] = ids_src[p];
  }
};

// Gathers the markers' canonical arrays (normals where the marker rule keeps them) into sorted order.
template <typename T>
struct GatherMarkers {
  MarkerArrays<T> src, dst;
  bool normals;
  const int* perm;
  TERRACAL_HD void operator()(long i) const {
    const int p = perm[i];
    dst.pos[i] = src.pos[p];
    dst.local[i] = src.local[p];
    dst.wall_vel[i] = src.wall_vel[p];
    if (normals) dst.normal[i] = src.normal[p];
  }
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
    for (int b = 0; b < count && !active; ++b) active = boxes[b].near(x, T(0));
    const T status = active ? T(kParticleActive) : T(kParticleFrozen);
    if (v.w != status) s.vel[i] = {active ? v.x : T(0), active ? v.y : T(0), active ? v.z : T(0), status};
  }
};

// The active domain's work lists (backends that compact it, B::kCompactsActive): the soil particles
// a stage integrates, and the markers it evaluates (those within the kernel's support of a box).
// Sorting with a skin (resolution.sort_skin): cells are 2h (1 + skin) / reach wide, so the stencil
// of `reach` cells around a particle's cell covers its support even where a neighbour has moved up to
// drift = 2 h skin out of the cell it was sorted into (per axis); the soil is sorted again only once
// some particle has moved further. This check sets *flag for a particle that has: outside the room
// (the sort marks it lost), or no longer within `drift` of a cell whose sorted range holds it, or (an
// active domain's boxes: box_count > 0) active but further than `drift` from every box, so that the
// markers listed within the support plus the drift of a box are all that active particles reach.
// begin: the cell ranges of the last sort; the lost particles are in the last one (SoilCellKey).
template <typename T>
struct SoilDriftCheck {
  GridGeometry<T> grid;
  const Vec4<T>* pos;
  const Vec4<T>* vel;
  const int* begin;
  Vec3<T> room_lo, room_hi;
  T drift;
  const ActiveBox<T>* boxes;
  int box_count;
  double* flag;
  TERRACAL_HD void operator()(long i) const {
    const int cells = grid.cells();
    const T status = vel[i].w;
    if (status == T(kParticleLost)) {
      if (i < begin[cells]) *flag = 1;
      return;
    }
    const Vec3<T> x = pos[i].xyz();
    if (box_count > 0 && status == T(kParticleActive) && !near_active(boxes, box_count, x, drift)) {
      *flag = 1;
      return;
    }
    const bool in_room = x.x >= room_lo.x && x.y >= room_lo.y && x.z >= room_lo.z && x.x <= room_hi.x &&
                         x.y <= room_hi.y && x.z <= room_hi.z;
    int ix, iy, iz;
    if (!in_room || !grid.cell_coords(x, ix, iy, iz)) {
      *flag = 1;
      return;
    }
    // Per axis, the offsets of the cells within `drift` of x: 0, and -1 / +1 near a face.
    const T cell = T(1) / grid.inv_cell;
    const T f[3] = {(x.x - grid.origin.x) - T(ix) * cell, (x.y - grid.origin.y) - T(iy) * cell,
                    (x.z - grid.origin.z) - T(iz) * cell};
    const int at[3] = {ix, iy, iz}, size[3] = {grid.nx, grid.ny, grid.nz};
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = f[a] <= drift && at[a] > 0 ? -1 : 0;
      hi[a] = cell - f[a] <= drift && at[a] + 1 < size[a] ? 1 : 0;
    }
    for (int dz = lo[2]; dz <= hi[2]; ++dz)
      for (int dy = lo[1]; dy <= hi[1]; ++dy)
        for (int dx = lo[0]; dx <= hi[0]; ++dx) {
          const int c = (ix + dx) + grid.nx * ((iy + dy) + grid.ny * (iz + dz));
          if (begin[c] <= i && i < begin[c + 1]) return;
        }
    *flag = 1;
  }
  TERRACAL_HD void operator()(long i, const LaneGroup&) const { (*this)(i); }
};

template <typename T>
struct IsActiveSoil {
  const Vec4<T>* vel;
  TERRACAL_HD bool operator()(int i) const { return vel[i].w == T(kParticleActive); }
};
template <typename T>
struct IsMarkerNearActive {
  const Vec4<T>* pos;
  const ActiveBox<T>* boxes;
  int count;
  T support;
  TERRACAL_HD bool operator()(int m) const { return near_active(boxes, count, pos[m].xyz(), support); }
};

}  // namespace terracal
