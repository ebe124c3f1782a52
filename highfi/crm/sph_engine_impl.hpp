#pragma once
// The step algorithm, written once over a backend B that supplies memory, parallel_for, a stable
// sort by cell and reductions (sph_engine_cpu.cpp, sph_engine_cuda.cu). Included by both.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "highfi/crm/marker_stage.hpp"
#include "highfi/crm/soil_stage.hpp"
#include "highfi/crm/sph_engine.hpp"
#include "highfi/crm/sph_sort.hpp"

namespace terracal {

template <typename T>
inline Vec4<T> to_t(const Vec4<double>& v) {
  return {T(v.x), T(v.y), T(v.z), T(v.w)};
}
template <typename T>
inline Vec3<T> to_t(const Vec3<double>& v) {
  return {T(v.x), T(v.y), T(v.z)};
}

template <typename T>
SphConstants<T> constants_in(const SphConstants<double>& c) {
  SphConstants<T> k;
  k.kernel.type = c.kernel.type;
  k.kernel.h = T(c.kernel.h);
  k.kernel.inv_h = T(c.kernel.inv_h);
  k.kernel.alpha = T(c.kernel.alpha);
  k.model = {T(c.model.shear_modulus),  T(c.model.bulk_modulus), T(c.model.mu_s),    T(c.model.mu_2), T(c.model.I0),
             T(c.model.grain_diameter), T(c.model.rho0),         T(c.model.cohesion)};
  k.mass = T(c.mass);
  k.gravity = to_t<T>(c.gravity);
  k.free_surface_support = T(c.free_surface_support);
  k.spacing = T(c.spacing);
  k.marker_velocity = c.marker_velocity;
  k.wall_contact = T(c.wall_contact);
  k.wall_contact_inv_reach = T(c.wall_contact_inv_reach);
  return k;
}
template <typename T>
GridGeometry<T> grid_in(const GridGeometry<double>& g) {
  return {to_t<T>(g.origin), T(g.inv_cell), g.nx, g.ny, g.nz, g.reach};
}

// Calls f(slot) for the record slot of every named effect that keeps a record per particle.
inline void for_each_named_record(const CrmEffectSet& effects, const std::function<void(int)>& f) {
  effects.for_each_named([&](auto tag) {
    using E = typename decltype(tag)::type;
    if constexpr (E::kRecord) f(kRecordSlot<E>);
  });
}

// Device-side storage of one soil state: four Vec4 arrays, and one per named effect with a record.
template <typename T, typename B>
struct SoilBuffers {
  SoilArrays<T> a;
  void allocate(std::size_t n, const CrmEffectSet& effects) {
    a.pos = B::template alloc<Vec4<T>>(n);
    a.vel = B::template alloc<Vec4<T>>(n);
    a.s0 = B::template alloc<Vec4<T>>(n);
    a.s1 = B::template alloc<Vec4<T>>(n);
    for_each_named_record(effects, [&](int slot) { a.record[slot] = B::template alloc<Vec4<T>>(n); });
  }
  void release() {
    B::release(a.pos);
    B::release(a.vel);
    B::release(a.s0);
    B::release(a.s1);
    for (Vec4<T>* r : a.record)
      if (r) B::release(r);
  }
};

// Where a backend's sort_pairs left its result (one of the caller's double buffers).
struct SortedPairs {
  const int* keys;
  const int* values;
};

// The four int arrays of a sort by cell (keys, values and their alternates, n each), laid over an
// array of n Vec4 records that is free while the sort and its gathers run: a record holds four ints.
struct SortArrays {
  int *keys, *vals, *keys_alt, *vals_alt;
  template <typename T>
  static SortArrays in(Vec4<T>* records, std::size_t n) {
    static_assert(sizeof(Vec4<T>) >= 4 * sizeof(int));
    int* p = reinterpret_cast<int*>(records);
    return {p, p + n, p + 2 * n, p + 3 * n};
  }
};

template <typename T, typename B>
class SphEngineImpl final : public SphEngine {
 public:
  explicit SphEngineImpl(const EngineSetup& s)
      : k_(constants_in<T>(s.constants)),
        ec_(s.template effect_constants<T>()),
        effects_(s.effects),
        grid_(grid_in<T>(s.grid)),
        n_(s.soil.size()),
        nm_(s.markers.size()),
        bodies_(s.bodies),
        room_lo_(to_t<T>(s.room_lo)),
        room_hi_(to_t<T>(s.room_hi)),
        drift_(s.sort_drift) {
    B::bind(n_);  // before any allocation: where this engine's work goes (the CUDA stream)
    for_each_named_record(effects_, [&](int) { ++records_; });
    const std::size_t nn = n_ > 0 ? n_ : 1, mm = nm_ > 0 ? nm_ : 1;
    A_.allocate(nn, effects_);
    B_.allocate(nn, effects_);
    ids_ = B::template alloc<int>(nn);
    const std::size_t cells = std::size_t(grid_.cells()) + 2;
    soil_begin_ = B::template alloc<int>(cells);
    marker_begin_ = B::template alloc<int>(cells);
    mk_.pos = B::template alloc<Vec4<T>>(mm);
    mk_.vel = B::template alloc<Vec4<T>>(mm);
    mk_.s0 = B::template alloc<Vec4<T>>(mm);
    mk_.s1 = B::template alloc<Vec4<T>>(mm);
    mk_.local = B::template alloc<Vec4<T>>(mm);
    mk_.wall_vel = B::template alloc<Vec4<T>>(mm);
    mk_.force = B::template alloc<Vec4<T>>(mm);
    // Normals only for the marker rules that need them: the others neither store nor sort them.
    const std::size_t mn = needs_wall_normals(k_.marker_velocity) ? mm : 1;
    mk_.normal = B::template alloc<Vec4<T>>(mn);
    canon_.pos = B::template alloc<Vec4<T>>(mm);
    canon_.local = B::template alloc<Vec4<T>>(mm);
    canon_.wall_vel = B::template alloc<Vec4<T>>(mm);
    canon_.normal = B::template alloc<Vec4<T>>(mn);
    poses_ = B::template alloc<BodyPose<T>>(std::size_t(bodies_));
    boxes_ = B::template alloc<ActiveBox<T>>(16);
    wrench_ = B::template alloc<double>(6 * std::size_t(bodies_) + 1);  // + the drift check's flag
    upload(s.soil);
    upload_markers(s.markers);
    std::vector<BodyPose<double>> rest(static_cast<std::size_t>(bodies_));
    set_poses(rest);
  }
  ~SphEngineImpl() override {
    A_.release();
    B_.release();
    for (int* p : {ids_, soil_begin_, marker_begin_}) B::release(p);
    Vec4<T>* const marker_fields[] = {mk_.pos,   mk_.vel,    mk_.s0,     mk_.s1,       mk_.local,       mk_.wall_vel,
                                      mk_.force, mk_.normal, canon_.pos, canon_.local, canon_.wall_vel, canon_.normal};
    for (Vec4<T>* p : marker_fields) B::release(p);
    B::release(poses_);
    B::release(boxes_);
    B::release(wrench_);
    for (int* p : {soil_list_, marker_list_, list_counts_, fixed_run_, moving_list_}) B::release(p);
  }

  std::string description() const override { return B::name() + (sizeof(T) == 8 ? " float64" : " float32"); }
  std::size_t soil_count() const override { return n_; }
  std::size_t marker_count() const override { return nm_; }
  std::size_t device_bytes() const override {
    const std::size_t per_soil = 2 * (4 + std::size_t(records_)) * sizeof(Vec4<T>) + sizeof(int);
    const std::size_t per_marker = (needs_wall_normals(k_.marker_velocity) ? 12 : 10) * sizeof(Vec4<T>);
    const std::size_t lists = list_counts_ ? (n_ + nm_ + 2) * sizeof(int) : 0;
    const std::size_t runs = (n_moving_ > 0 ? std::size_t(n_fixed_ + n_moving_) : 0) * sizeof(int);
    return n_ * per_soil + nm_ * per_marker + 2 * (std::size_t(grid_.cells()) + 2) * sizeof(int) + lists + runs +
           B::scratch_bytes();
  }

  void set_poses(const std::vector<BodyPose<double>>& poses) override {
    std::vector<BodyPose<T>> p(poses.size());
    bool any_moving = false;
    for (std::size_t b = 0; b < poses.size(); ++b) {
      p[b].center = to_t<T>(poses[b].center);
      p[b].velocity = to_t<T>(poses[b].velocity);
      p[b].omega = to_t<T>(poses[b].omega);
      for (int q = 0; q < 9; ++q) p[b].R[q] = T(poses[b].R[q]);
      p[b].moving = poses[b].moving;
      any_moving = any_moving || poses[b].moving;
    }
    B::upload_async(poses_, p.data(), p.size());
    if (nm_ == 0) {
      sort_markers();
      return;
    }
    if (any_moving && markers_within_drift(poses)) {
      // Moved, but not beyond the reach of their cells: new positions in place, no sort.
      B::parallel_for(long(nm_), MarkerPoseUpdate<T>{poses_, mk_});
      ++sorts_.markers_moved;
      return;
    }
    if (any_moving) {
      prepare_marker_runs(poses);
      // Only the moving markers, where they are listed (MarkerPoseUpdate leaves the others).
      if (n_moving_ > 0)
        B::parallel_for(long(n_moving_), ListedMarkerPoseUpdate<T>{{poses_, canon_}, moving_list_});
      else
        B::parallel_for(long(nm_), MarkerPoseUpdate<T>{poses_, canon_});
    }
    if (any_moving || !markers_sorted_) {
      sort_markers();
      sorted_poses_ = poses;
    }
  }

  void set_active(const std::vector<ActiveBox<double>>& boxes) override {
    if (boxes.size() > 16) throw RunError("active_domain: at most 16 moving bodies");
    if (boxes_within_drift(boxes)) return;
    applied_boxes_ = boxes;
    boxes_applied_ = true;
    carry_stale_ = true;
    std::vector<ActiveBox<T>> b(boxes.size());
    for (std::size_t q = 0; q < boxes.size(); ++q) b[q] = {to_t<T>(boxes[q].lo), to_t<T>(boxes[q].hi)};
    if (!b.empty()) B::upload_async(boxes_, b.data(), b.size());
    active_boxes_ = int(b.size());
    if (b.empty()) {
      // Everyone active: a single box that covers the whole grid.
      ActiveBox<T> all{grid_.origin,
                       grid_.origin + (T(1) / grid_.inv_cell) * Vec3<T>{T(grid_.nx), T(grid_.ny), T(grid_.nz)}};
      B::upload_async(boxes_, &all, 1);
    }
    B::parallel_for(long(n_), MarkActive<T>{boxes_, int(std::max<std::size_t>(b.size(), 1)), A_.a});
    if constexpr (B::kCompactsActive) {
      if (!b.empty() && !list_counts_) {
        soil_list_ = B::template alloc<int>(n_ > 0 ? n_ : 1);
        marker_list_ = B::template alloc<int>(nm_ > 0 ? nm_ : 1);
        list_counts_ = B::template alloc<int>(2);
      }
    }
    soil_list_stale_ = marker_list_stale_ = true;
  }

  // The sort's four key and value arrays live in memory that is free while it runs (SortArrays), so
  // that sorting costs no memory of its own: the soil's in B's s1, the markers' in their forces.
  void begin_step() override {
    if (drift_ > 0 && !soil_resort_) return;  // every particle within reach of its cell: no sort
    soil_resort_ = false;
    carry_stale_ = true;
    ++sorts_.soil;
    if (drift_ > 0) B::zero(wrench_ + 6 * bodies_, 1);  // the drift check's flag
    if (n_ == 0) {
      B::fill_begin(soil_begin_, grid_.cells() + 2, 0);
      return;
    }
    // B is scratch between steps (it held the midpoint state), and its s1 holds the sort's arrays.
    const SortArrays sa = SortArrays::in(B_.a.s1, n_);
    B::parallel_for(long(n_), SoilCellKey<T>{grid_, A_.a, room_lo_, room_hi_, sa.keys, sa.vals});
    const int* sorted =
        B::sort_cells(int(n_), grid_.cells() + 1, sa.keys, sa.vals, sa.keys_alt, sa.vals_alt, soil_begin_);
    // Gather A into B in sorted order, then swap. Once A's positions are gathered their memory is
    // free: the permutation moves there, out of the way of the gather into B's s1.
    B::parallel_for(long(n_), Gather<Vec4<T>>{A_.a.pos, B_.a.pos, sorted});
    const SortArrays moved = SortArrays::in(A_.a.pos, n_);
    B::copy(moved.keys, sorted, n_);
    const int* perm = moved.keys;
    B::parallel_for(long(n_), GatherSoil<T>{A_.a, B_.a, ids_, moved.vals, perm});
    B::copy(ids_, moved.vals, n_);
    std::swap(A_, B_);
    soil_list_stale_ = true;
  }

  std::vector<double> stage(int which, double dt, bool want_wrench) override {
    const SoilArrays<T> eval = which == 0 ? A_.a : B_.a;
    const SoilArrays<T> out = which == 0 ? B_.a : A_.a;
    const T h = T(which == 0 ? 0.5 * dt : dt);
    run_stage(eval, out, h);
    // After the step's last stage, whether the next step must sort: its flag comes back with the wrench.
    const bool check = drift_ > 0 && which == 1;
    if (check) check_drift();
    const std::size_t nw = 6 * std::size_t(bodies_);
    std::vector<double> w(nw + 1, 0.0);
    if (nm_ > 0 && (want_wrench || which == 1))
      B::wrench_sum(mk_, long(nm_), poses_, bodies_, wrench_, w.data(), check ? 1 : 0);
    else if (check)
      B::download(w.data() + nw, wrench_ + nw, 1);
    if (check && w[nw] != 0) soil_resort_ = true;
    w.resize(nw);
    return w;
  }

  SortCounts sort_counts() const override { return sorts_; }
  SoilStats stats() const override { return B::soil_stats(A_.a, long(n_), double(k_.mass), k_.model); }

  // A copy of the soil that leaves the engine (a checkpoint) is followed by a sort of soil and
  // markers, as the restart from it begins with one: the two go on in the same order.
  void download(HostSoil& s) const override {
    soil_resort_ = true;
    markers_sorted_ = false;
    s.pos.resize(n_);
    s.vel.resize(n_);
    s.s0.resize(n_);
    s.s1.resize(n_);
    s.ids.resize(n_);
    download_vec4(A_.a.pos, s.pos);
    download_vec4(A_.a.vel, s.vel);
    download_vec4(A_.a.s0, s.s0);
    download_vec4(A_.a.s1, s.s1);
    for (auto& r : s.records) r.clear();
    for_each_named_record(effects_, [&](int r) {
      s.records[r].resize(n_);
      download_vec4(A_.a.record[r], s.records[r]);
    });
    B::download(s.ids.data(), ids_, n_);
  }

  void upload(const HostSoil& s) override {
    if (s.size() != n_) throw RunError("engine upload: particle count changed");
    upload_vec4(A_.a.pos, s.pos);
    upload_vec4(A_.a.vel, s.vel);
    upload_vec4(A_.a.s0, s.s0);
    upload_vec4(A_.a.s1, s.s1);
    for_each_named_record(effects_, [&](int r) {
      // A bed settled without the effect starts with a zero record.
      std::vector<Vec4<double>> record = s.records[r];
      if (record.size() != n_) record.assign(n_, Vec4<double>{0, 0, 0, 0});
      upload_vec4(A_.a.record[r], record);
    });
    B::upload(ids_, s.ids.data(), n_);
    soil_list_stale_ = true;
    soil_resort_ = true;
    markers_sorted_ = false;
  }

 private:
  // The passes are compiled for each list of named effects (core/effect_list.hpp, with_named), so
  // that an effect a scene does not name costs nothing in them.
  void run_stage(const SoilArrays<T>& eval, const SoilArrays<T>& out, T dt) {
    if constexpr (B::kCompactsActive) {
      if (active_boxes_ > 0) return run_listed_stage(eval, out, dt);
    }
    if (nm_ > 0)
      with_named<InMarkerLoop>(effects_, [&](auto mx) {
        B::parallel_for_heavy(long(nm_), MarkerStage<T, decltype(mx)>{k_, ec_, grid_, soil_begin_, eval, mk_, poses_,
                                                                      boxes_, active_boxes_, box_reach()});
      });
    if (n_ == 0) return;
    with_named<InSoilLoop>(effects_, [&](auto fx) {
      B::parallel_for_heavy(
          long(n_), SoilStage<T, decltype(fx)>{k_, ec_, grid_, soil_begin_, marker_begin_, eval, A_.a, out, mk_, dt});
    });
  }

  // The active domain on a backend that compacts it (the GPU): the stages run over lists of the busy
  // markers and particles, a group of lanes each (core/lane_group.hpp), and the frozen particles are
  // carried by a plain copy. With a few thousand particles busy, a stage otherwise waits on one
  // thread's walk through its neighbours, in every wave of a launch over the whole bed.
  void run_listed_stage(const SoilArrays<T>& eval, const SoilArrays<T>& out, T dt) {
    if constexpr (B::kCompactsActive) {
      const int lanes = stage_lanes();
      if (nm_ > 0) {
        // The markers off the list exert no force; the listed ones' forces are written by every stage,
        // so the forces are cleared only with a new list (a sort of the markers borrows their memory).
        if (marker_list_stale_) {
          B::select(long(nm_), IsMarkerNearActive<T>{mk_.pos, boxes_, active_boxes_, box_reach()},
                    marker_list_, list_counts_ + 1);
          B::zero(mk_.force, nm_);
        }
        marker_list_stale_ = false;
        with_named<InMarkerLoop>(effects_, [&](auto mx) {
          B::parallel_for_listed(
              marker_list_, list_counts_ + 1, long(nm_),
              MarkerStage<T, decltype(mx)>{k_, ec_, grid_, soil_begin_, eval, mk_, poses_, boxes_, active_boxes_,
                                           box_reach()},
              lanes);
        });
      }
      if (n_ == 0) return;
      if (soil_list_stale_) B::select(long(n_), IsActiveSoil<T>{A_.a.vel}, soil_list_, list_counts_);
      soil_list_stale_ = false;
      with_named<InSoilLoop>(effects_, [&](auto fx) {
        using Stage = SoilStage<T, decltype(fx)>;
        const Stage stage{k_, ec_, grid_, soil_begin_, marker_begin_, eval, A_.a, out, mk_, dt};
        // B keeps the frozen particles' state from the last copy until a sort or new boxes move them.
        if (out.pos != A_.a.pos && carry_stale_) {
          B::parallel_for(long(n_), typename Stage::CarryFrozen{stage});
          carry_stale_ = false;
        }
        B::parallel_for_listed(soil_list_, list_counts_, long(n_), stage, lanes);
      });
    }
  }

  // How far from an active domain's boxes the markers take part in a stage (are listed, on the GPU):
  // the kernel's support, and with a skin also the drift, as far as an active particle may stray from
  // its box before the next sort (SoilDriftCheck), so that every marker an active particle reaches is
  // updated.
  T box_reach() const { return std::sqrt(k_.kernel.support2()) + T(drift_); }

  // Whether every moving body's markers are still within the drift of the cells of their last sort:
  // a marker at l in its body moves by at most |dc| + |dR|_F |l|.
  bool markers_within_drift(const std::vector<BodyPose<double>>& poses) const {
    if (!(drift_ > 0) || !markers_sorted_ || sorted_poses_.size() != poses.size()) return false;
    for (std::size_t b = 0; b < poses.size(); ++b) {
      const BodyPose<double>&a = poses[b], &o = sorted_poses_[b];
      if (a.moving != o.moving) return false;
      if (!a.moving) continue;
      double dr = 0;
      for (int q = 0; q < 9; ++q) dr += (a.R[q] - o.R[q]) * (a.R[q] - o.R[q]);
      const double radius = b < body_radius_.size() ? body_radius_[b] : 0;
      if (norm(a.center - o.center) + std::sqrt(dr) * radius > drift_) return false;
    }
    return true;
  }

  // Whether the active boxes may stay as they were applied: with a skin, until the soil's next sort
  // or until one has moved by more than the drift (the frozen soil then changes only at sorts, and
  // the boxes lag their bodies by at most the drift).
  bool boxes_within_drift(const std::vector<ActiveBox<double>>& boxes) const {
    if (!(drift_ > 0) || soil_resort_ || !boxes_applied_ || boxes.size() != applied_boxes_.size()) return false;
    for (std::size_t q = 0; q < boxes.size(); ++q) {
      const Vec3<double> dlo = boxes[q].lo - applied_boxes_[q].lo, dhi = boxes[q].hi - applied_boxes_[q].hi;
      for (double d : {dlo.x, dlo.y, dlo.z, dhi.x, dhi.y, dhi.z})
        if (std::abs(d) > drift_) return false;
    }
    return true;
  }

  // Sets the flag (after the wrench) when a particle has left the reach of its cell (SoilDriftCheck).
  void check_drift() {
    if (n_ == 0) return;
    const SoilDriftCheck<T> c{grid_,  A_.a.pos,     A_.a.vel, soil_begin_,          room_lo_,
                              room_hi_, T(drift_), boxes_,   active_boxes_, wrench_ + 6 * bodies_};
    if constexpr (B::kCompactsActive) {
      if (active_boxes_ > 0) return B::parallel_for_listed(soil_list_, list_counts_, long(n_), c, 1);
    }
    B::parallel_for(long(n_), c);
  }

  // Threads per item in the listed stages (run_listed_stage; docs/decisions.md, "Active domain on
  // the GPU"). TERRACAL_CUDA_LANES (1, 2, 4, 8, 16 or 32) overrides it for tuning runs.
  static int stage_lanes() {
    static const int forced = [] {
      const char* e = std::getenv("TERRACAL_CUDA_LANES");
      const int v = e ? std::atoi(e) : 0;
      return v >= 1 && v <= 32 && (v & (v - 1)) == 0 ? v : 0;
    }();
    return forced ? forced : kActiveDomainLanes;
  }
  static constexpr int kActiveDomainLanes = 8;

  // Markers are re-derived from their canonical (construction-order) arrays at every sort, so that
  // their sorted order depends only on the current poses, never on the history: a run restarted
  // from a checkpoint sums in exactly the same order as one that went on.
  void sort_markers() {
    if (nm_ == 0) {
      B::fill_begin(marker_begin_, grid_.cells() + 2, 0);
      markers_sorted_ = true;
      return;
    }
    // The markers' forces are rewritten by every stage before they are read, so the sort borrows them.
    const SortArrays sa = SortArrays::in(mk_.force, nm_);
    const int* perm = nullptr;
    if (B::kMergesMarkerRuns && n_moving_ > 0) {
      if constexpr (B::kMergesMarkerRuns) perm = merge_marker_runs(sa);
      ++sorts_.markers_merged;
    } else {
      ++sorts_.markers_full;
      B::parallel_for(long(nm_), MarkerCellKey<T>{grid_, canon_, sa.keys, sa.vals});
      perm = B::sort_cells(int(nm_), grid_.cells() + 1, sa.keys, sa.vals, sa.keys_alt, sa.vals_alt, marker_begin_);
    }
    B::parallel_for(long(nm_), GatherMarkers<T>{canon_, mk_, needs_wall_normals(k_.marker_velocity), perm});
    markers_sorted_ = true;
    marker_list_stale_ = true;
  }

  // The markers split in two runs for sort_markers (MergeMarkerRuns), on a backend whose sorts pay for
  // the length sorted (B::kMergesMarkerRuns: the GPU): those of the bodies that do not move, sorted
  // here once, and those of the moving bodies, sorted at every pose. Made again only when
  // the set of moving bodies changes. Where the moving markers are more than half (the sort's arrays
  // hold 4 of theirs next to 2 of everyone's), every marker is sorted at every pose as before.
  void prepare_marker_runs(const std::vector<BodyPose<double>>& poses) {
    if (!B::kMergesMarkerRuns || !merge_markers_) return;
    std::vector<char> moving(poses.size());
    for (std::size_t b = 0; b < poses.size(); ++b) moving[b] = poses[b].moving ? 1 : 0;
    if (moving == runs_moving_) return;
    runs_moving_ = moving;
    std::vector<int> fixed, moved;
    for (std::size_t m = 0; m < marker_body_.size(); ++m) {
      const int b = marker_body_[m];
      (b >= 0 && std::size_t(b) < moving.size() && moving[std::size_t(b)] ? moved : fixed).push_back(int(m));
    }
    B::release(fixed_run_);
    B::release(moving_list_);
    fixed_run_ = moving_list_ = nullptr;
    n_fixed_ = n_moving_ = 0;
    if (moved.empty() || 2 * moved.size() > nm_) return;
    fixed_run_ = B::template alloc<int>(fixed.size());
    moving_list_ = B::template alloc<int>(moved.size());
    B::upload(moving_list_, moved.data(), moved.size());
    if (!fixed.empty()) {
      // Sort the fixed markers by cell once, in the sort's borrowed arrays (the positions of the
      // fixed markers are the canonical ones and never change).
      const SortArrays sa = SortArrays::in(mk_.force, nm_);
      B::upload(sa.vals, fixed.data(), fixed.size());
      const long nf = long(fixed.size());
      B::parallel_for(nf, MarkerSubsetCellKey<T>{grid_, canon_.pos, sa.vals, sa.keys, sa.vals});
      if constexpr (B::kMergesMarkerRuns) {
        const SortedPairs sorted =
            B::sort_pairs(int(nf), grid_.cells() + 1, sa.keys, sa.vals, sa.keys_alt, sa.vals_alt);
        B::copy(fixed_run_, sorted.values, fixed.size());
      }
    }
    n_fixed_ = int(fixed.size());
    n_moving_ = int(moved.size());
    markers_sorted_ = false;
  }

  // sort_markers with two runs: only the moving markers are sorted; the merge places everyone.
  // Arrays (SortArrays over the markers' forces): keys and perm take everyone's first two quarters,
  // the moving markers' keys and values and their alternates the rest.
  const int* merge_marker_runs(const SortArrays& sa) {
    static_assert(B::kMergesMarkerRuns);
    const long nv = n_moving_;
    int* mkeys = sa.keys_alt;
    int* mvals = mkeys + nv;
    int* mkeys_alt = mvals + nv;
    int* mvals_alt = mkeys_alt + nv;
    B::parallel_for(nv, MarkerSubsetCellKey<T>{grid_, canon_.pos, moving_list_, mkeys, mvals});
    const SortedPairs moving = B::sort_pairs(int(nv), grid_.cells() + 1, mkeys, mvals, mkeys_alt, mvals_alt);
    B::parallel_for(long(nm_), MergeMarkerRuns<T>{grid_, canon_.pos, fixed_run_, n_fixed_, moving.keys, moving.values,
                                                  n_moving_, sa.keys, sa.vals});
    B::cell_begin(sa.keys, int(nm_), grid_.cells() + 1, marker_begin_);
    return sa.vals;
  }

  void upload_markers(const HostMarkers& m) {
    marker_body_.resize(m.local.size());
    for (std::size_t q = 0; q < m.local.size(); ++q) {
      const Vec4<double>& l = m.local[q];
      marker_body_[q] = int(std::lround(l.w));
      const std::size_t b = std::size_t(std::max(marker_body_[q], 0));
      if (body_radius_.size() <= b) body_radius_.resize(b + 1, 0.0);
      body_radius_[b] = std::max(body_radius_[b], std::sqrt(l.x * l.x + l.y * l.y + l.z * l.z));
    }
    upload_vec4(canon_.pos, m.pos);
    upload_vec4(canon_.local, m.local);
    upload_vec4(canon_.wall_vel, m.wall_vel);
    if (needs_wall_normals(k_.marker_velocity)) {
      std::vector<Vec4<double>> normal = m.normal;
      normal.resize(m.pos.size(), Vec4<double>{0, 0, 0, 0});
      upload_vec4(canon_.normal, normal);
    }
    markers_sorted_ = false;
  }
  void upload_vec4(Vec4<T>* dst, const std::vector<Vec4<double>>& src) {
    std::vector<Vec4<T>> t(src.size());
    for (std::size_t i = 0; i < src.size(); ++i) t[i] = to_t<T>(src[i]);
    B::upload(dst, t.data(), t.size());
  }
  void download_vec4(const Vec4<T>* src, std::vector<Vec4<double>>& dst) const {
    std::vector<Vec4<T>> t(dst.size());
    B::download(t.data(), src, t.size());
    for (std::size_t i = 0; i < t.size(); ++i)
      dst[i] = {double(t[i].x), double(t[i].y), double(t[i].z), double(t[i].w)};
  }

  SphConstants<T> k_;
  CrmEffectConstants<T> ec_;
  CrmEffectSet effects_;
  int records_ = 0;  // arrays of effect records per soil state
  GridGeometry<T> grid_;
  std::size_t n_, nm_;
  int bodies_;
  Vec3<T> room_lo_, room_hi_;
  // Sorting with a skin (EngineSetup::sort_drift; 0: at every step): whether the soil is sorted at
  // the next step, the poses of the markers' last sort, each body's marker radius, the boxes applied.
  double drift_ = 0;
  mutable bool soil_resort_ = true;
  std::vector<BodyPose<double>> sorted_poses_;
  std::vector<double> body_radius_;
  std::vector<ActiveBox<double>> applied_boxes_;
  bool boxes_applied_ = false;
  bool carry_stale_ = true;  // B's frozen particles differ from A's (a sort or new boxes since the copy)
  mutable bool markers_sorted_ = false;
  int active_boxes_ = 0;  // the active domain's boxes (0: every particle is active)
  SoilBuffers<T, B> A_, B_;
  MarkerArrays<T> mk_;
  MarkerArrays<T> canon_;  // construction order: pos, local, wall_vel, normal
  int* ids_ = nullptr;
  int *soil_begin_ = nullptr, *marker_begin_ = nullptr;
  BodyPose<T>* poses_ = nullptr;
  ActiveBox<T>* boxes_ = nullptr;
  double* wrench_ = nullptr;
  // The active domain's lists on a backend that compacts it (run_listed_stage), made when stale.
  int *soil_list_ = nullptr, *marker_list_ = nullptr, *list_counts_ = nullptr;
  bool soil_list_stale_ = true, marker_list_stale_ = true;
  // The markers' two runs (prepare_marker_runs): each canonical marker's body, the fixed run sorted
  // by (cell, index), the moving markers' indices; the moving flags they were made for.
  std::vector<int> marker_body_;
  int *fixed_run_ = nullptr, *moving_list_ = nullptr;
  int n_fixed_ = 0, n_moving_ = 0;
  std::vector<char> runs_moving_;
  SortCounts sorts_;
  // TERRACAL_CRM_SORT_ALL=1 sorts every marker at every pose instead of merging two runs: the same
  // order the long way, for timing runs and the tests that compare.
  bool merge_markers_ = [] {
    const char* e = std::getenv("TERRACAL_CRM_SORT_ALL");
    return !(e && std::string(e) == "1");
  }();
};

}  // namespace terracal
