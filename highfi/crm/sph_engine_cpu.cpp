// The CPU backend of the CRM engine: host memory, OpenMP loops, a stable counting sort by cell
// and double-precision reductions. The physics is the shared functors of soil_stage.hpp and
// marker_stage.hpp (through sph_engine_impl.hpp).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include <omp.h>

#include "core/errors.hpp"
#include "core/parallel_for.hpp"
#include "highfi/crm/sph_engine_impl.hpp"

namespace terracal {
namespace {

struct CpuBackend {
  static std::string name() { return "CPU (OpenMP, " + std::to_string(omp_get_max_threads()) + " threads)"; }
  static std::size_t scratch_bytes() { return 0; }
  static void bind(std::size_t /*particles*/) {}
  // 8 records of padding: the SIMD neighbour filter reads up to 7 records past a row's end.
  template <typename U>
  static U* alloc(std::size_t n) {
    return new U[n + 8]();
  }
  template <typename U>
  static void release(U* p) {
    delete[] p;
  }
  template <typename U>
  static void upload(U* dst, const U* src, std::size_t n) {
    if (n) std::memcpy(static_cast<void*>(dst), src, n * sizeof(U));
  }
  template <typename U>
  static void upload_async(U* dst, const U* src, std::size_t n) {
    upload(dst, src, n);
  }
  template <typename U>
  static void download(U* dst, const U* src, std::size_t n) {
    if (n) std::memcpy(static_cast<void*>(dst), src, n * sizeof(U));
  }
  template <typename U>
  static void copy(U* dst, const U* src, std::size_t n) {
    if (n) std::memcpy(static_cast<void*>(dst), src, n * sizeof(U));
  }
  template <typename U>
  static void zero(U* p, std::size_t n) {
    std::fill(p, p + n, U{});
  }
  template <typename F>
  static void parallel_for(long n, const F& f) {
    parallel_for_cpu(n, f);
  }
  // The active domain's frozen particles are skipped inside the loops: on the CPU that costs a test
  // each, and the loops need no lists.
  static constexpr bool kCompactsActive = false;
  template <typename F>
  static void parallel_for_heavy(long n, const F& f) {
    parallel_for_cpu_balanced(n, f);
  }
  static void fill_begin(int* begin, int count, int value) { std::fill(begin, begin + count, value); }

  // The markers are sorted whole at every pose: the counting sort passes over every cell either way,
  // and merging two runs cost more than it saved here (bench/RESULTS.md, "Markers sorted from two
  // runs").
  static constexpr bool kMergesMarkerRuns = false;
  // Stable counting sort of values by key (keys in [0, bins)); begin[c] is the first sorted index of
  // cell c (size bins + 1). Stable, so it gives the same order as the GPU's radix sort.
  static const int* sort_cells(int n, int bins, int* keys, int* vals, int* /*keys_alt*/, int* vals_alt, int* begin) {
    std::fill(begin, begin + bins + 1, 0);
    for (int i = 0; i < n; ++i) ++begin[keys[i] + 1];
    for (int c = 0; c < bins; ++c) begin[c + 1] += begin[c];
    std::vector<int> next(begin, begin + bins);
    for (int i = 0; i < n; ++i) vals_alt[next[std::size_t(keys[i])]++] = vals[i];
    return vals_alt;
  }

  // out = the bodies' wrenches, then `extra` values that follow them in scratch (a flag).
  template <typename T>
  static void wrench_sum(const MarkerArrays<T>& mk, long nm, const BodyPose<T>* poses, int bodies, double* scratch,
                         double* out, int extra) {
    std::fill(out, out + 6 * bodies, 0.0);
    std::copy(scratch + 6 * bodies, scratch + 6 * bodies + extra, out + 6 * bodies);
    for (long m = 0; m < nm; ++m) {
      const int b = int(mk.local[m].w);
      const Vec3<double> c{double(poses[b].center.x), double(poses[b].center.y), double(poses[b].center.z)};
      add_marker_wrench(mk, m, c, out + 6 * b);
    }
  }

  template <typename T>
  static SoilStats soil_stats(const SoilArrays<T>& s, long n, double mass, const SoilModel<T>& model) {
    SoilStats st;
    double ke = 0, px = 0, py = 0, pz = 0, mx = 0, my = 0, mz = 0, vmax = 0;
    long bad = 0, lost = 0, frozen = 0, capped = 0;
#pragma omp parallel for reduction(+ : ke, px, py, pz, mx, my, mz, bad, lost, frozen, capped) reduction(max : vmax)
    for (long i = 0; i < n; ++i) {
      const Vec4<T> v = s.vel[i], p = s.pos[i];
      const double vx = v.x, vy = v.y, vz = v.z;
      const bool finite = std::isfinite(vx) && std::isfinite(vy) && std::isfinite(vz) && std::isfinite(double(p.x)) &&
                          std::isfinite(double(p.y)) && std::isfinite(double(p.z)) && std::isfinite(double(p.w));
      if (!finite) {
        ++bad;
        continue;
      }
      if (v.w == T(kParticleLost)) {
        ++lost;
        continue;
      }
      if (v.w == T(kParticleFrozen))
        ++frozen;
      else if (at_density_cap(p.w, s.s0[i], model))
        ++capped;
      const double v2 = vx * vx + vy * vy + vz * vz;
      ke += 0.5 * mass * v2;
      px += mass * vx;
      py += mass * vy;
      pz += mass * vz;
      mx += mass * double(p.x);
      my += mass * double(p.y);
      mz += mass * double(p.z);
      vmax = std::max(vmax, std::sqrt(v2));
    }
    st.mass = mass * double(n - lost - bad);
    st.kinetic_energy = ke;
    st.momentum = {px, py, pz};
    st.first_moment = {mx, my, mz};
    st.max_speed = vmax;
    st.nonfinite = bad;
    st.lost = lost;
    st.frozen = frozen;
    st.at_density_cap = capped;
    return st;
  }
};

}  // namespace

std::unique_ptr<SphEngine> make_cpu_engine(const EngineSetup& setup, CrmPrecision precision) {
  if (precision == CrmPrecision::kDouble) return std::make_unique<SphEngineImpl<double, CpuBackend>>(setup);
  return std::make_unique<SphEngineImpl<float, CpuBackend>>(setup);
}

#if !defined(TERRACAL_HAVE_CUDA)
std::unique_ptr<SphEngine> make_cuda_engine(const EngineSetup&) {
  throw RunError("this terracal was built without CUDA (TERRACAL_CUDA=OFF or no nvcc): use --device cpu");
}
bool cuda_engine_available(std::string* why) {
  if (why) *why = "built without CUDA";
  return false;
}
#endif

}  // namespace terracal
