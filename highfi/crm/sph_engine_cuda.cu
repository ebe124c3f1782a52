// The CUDA backend of the CRM engine: device memory (never managed memory), the shared functors of
// soil_stage.hpp and marker_stage.hpp launched by parallel_for_cuda, CUB's stable radix sort by cell,
// and double-precision reductions with warp shuffles and atomics. Every call goes to its host thread's
// stream (ThreadStream): engines driven from different threads (CRM runs at once,
// core/concurrent_jobs.hpp) work side by side, and one engine's copies and waits do not wait for the
// others' kernels. What the backend keeps between calls is per host thread.
#include <thrust/iterator/counting_iterator.h>
#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_select.cuh>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>
#include <type_traits>

#include "core/cuda_check.hpp"
#include "core/parallel_for_cuda.cuh"
#include "highfi/crm/sph_engine_impl.hpp"

namespace terracal {
namespace {

constexpr int kDefaultMinBlocks = 4;  // the measured best (bench/RESULTS.md, "Occupancy"; docs/decisions.md)

// A stage's own choice of blocks per SM (F::kCudaMinBlocks), or the default.
template <typename F, typename = void>
struct PreferredMinBlocks : std::integral_constant<int, kDefaultMinBlocks> {};
template <typename F>
struct PreferredMinBlocks<F, std::void_t<decltype(F::kCudaMinBlocks)>>
    : std::integral_constant<int, F::kCudaMinBlocks> {};

// The stream of this host thread's engine. Small runs (under kHighPriorityBelow particles: a wheel, an
// annulus) get the device's highest stream priority and large ones (plates in their wide bins) the
// lowest: run at once, a small run's short kernels then take the next free SM instead of queuing
// behind a large run's, and the large run fills the rest (bench/RESULTS.md, "CRM runs at once").
// A thread whose next engine has the other priority first waits for its current stream, so that
// everything it queued is done before the other stream carries on.
constexpr std::size_t kHighPriorityBelow = 1000000;
struct ThreadStream {
  cudaStream_t streams[2] = {nullptr, nullptr};  // high, low priority
  int current = 0;
  ~ThreadStream() {
    for (cudaStream_t s : streams)
      if (s) cudaStreamDestroy(s);
  }
  cudaStream_t get() {
    if (!streams[current]) {
      int least = 0, greatest = 0;
      TERRACAL_CUDA_CHECK(cudaDeviceGetStreamPriorityRange(&least, &greatest));
      TERRACAL_CUDA_CHECK(
          cudaStreamCreateWithPriority(&streams[current], cudaStreamNonBlocking, current == 0 ? greatest : least));
    }
    return streams[current];
  }
  void choose(bool high) {
    const int want = high ? 0 : 1;
    if (want == current) return;
    if (streams[current]) TERRACAL_CUDA_CHECK(cudaStreamSynchronize(streams[current]));
    current = want;
  }
};
ThreadStream& thread_stream() {
  thread_local ThreadStream s;
  return s;
}
cudaStream_t stream() { return thread_stream().get(); }

// Device scratch (CUB's sort, the reductions' sums), grown on demand and kept for the host thread's
// lifetime: one per thread, so that engines on different threads never share it.
struct CubScratch {
  void* p = nullptr;
  std::size_t bytes = 0;
  ~CubScratch() {
    // At the thread's end, in its stream (constructed before this scratch, so destroyed after it):
    // cudaFree would wait for every other thread's kernels.
    if (p) cudaFreeAsync(p, stream());
  }
  void* ensure(std::size_t n) {
    if (n > bytes) {
      if (p) TERRACAL_CUDA_CHECK(cudaFreeAsync(p, stream()));
      TERRACAL_CUDA_CHECK(cudaMallocAsync(&p, n, stream()));
      bytes = n;
    }
    return p;
  }
};
CubScratch& cub_scratch() {
  thread_local CubScratch s;
  return s;
}
// The reductions' sums: allocated once per thread, not per call (cudaFree waits for the whole device,
// every other thread's stream included).
double* reduction_scratch(std::size_t count) {
  thread_local CubScratch s;
  return static_cast<double*>(s.ensure(count * sizeof(double)));
}

// Pinned host slots for upload_async, used in turn; a slot is reused once the copy queued from it has
// run (its event), which is long done: every step waits for its last stage's wrench.
struct PinnedStaging {
  static constexpr int kSlots = 8;
  static constexpr std::size_t kSlotBytes = 4096;
  char* memory = nullptr;
  cudaEvent_t done[kSlots] = {};
  int next = 0;
  ~PinnedStaging() {
    for (cudaEvent_t e : done)
      if (e) cudaEventDestroy(e);
    if (memory) cudaFreeHost(memory);
  }
  // Copies bytes into the next slot and returns it; null when they do not fit a slot.
  void* stage(const void* src, std::size_t bytes) {
    if (bytes > kSlotBytes) return nullptr;
    if (!memory) {
      TERRACAL_CUDA_CHECK(cudaMallocHost(reinterpret_cast<void**>(&memory), kSlots * kSlotBytes));
      for (cudaEvent_t& e : done) TERRACAL_CUDA_CHECK(cudaEventCreateWithFlags(&e, cudaEventDisableTiming));
    }
    TERRACAL_CUDA_CHECK(cudaEventSynchronize(done[next]));
    char* slot = memory + std::size_t(next) * kSlotBytes;
    std::memcpy(slot, src, bytes);
    return slot;
  }
  void queued(cudaStream_t s) {
    TERRACAL_CUDA_CHECK(cudaEventRecord(done[next], s));
    next = (next + 1) % kSlots;
  }
};
PinnedStaging& pinned_staging() {
  thread_local PinnedStaging s;
  return s;
}

struct FillInt {
  int* p;
  int v;
  __device__ void operator()(long i) const { p[i] = v; }
};

__device__ inline double warp_sum(double v) {
  for (int o = 16; o > 0; o >>= 1) v += __shfl_down_sync(0xffffffffu, v, o);
  return v;
}
__device__ inline double warp_max(double v) {
  for (int o = 16; o > 0; o >>= 1) v = fmax(v, __shfl_down_sync(0xffffffffu, v, o));
  return v;
}
// atomicMax for non-negative doubles: their bit patterns order like the values.
__device__ inline void atomic_max_nonneg(double* a, double v) {
  atomicMax(reinterpret_cast<unsigned long long*>(a), static_cast<unsigned long long>(__double_as_longlong(v)));
}

template <typename T>
__global__ void wrench_kernel(MarkerArrays<T> mk, long nm, const BodyPose<T>* poses, int bodies, double* out) {
  // Each thread sums a strided share per body; bodies are few (one pass per body keeps it simple).
  for (int b = 0; b < bodies; ++b) {
    double acc[6] = {0, 0, 0, 0, 0, 0};
    const Vec3<double> c{double(poses[b].center.x), double(poses[b].center.y), double(poses[b].center.z)};
    for (long m = blockIdx.x * long(blockDim.x) + threadIdx.x; m < nm; m += long(blockDim.x) * gridDim.x) {
      if (int(mk.local[m].w) != b) continue;
      add_marker_wrench(mk, m, c, acc);
    }
    for (int q = 0; q < 6; ++q) {
      const double s = warp_sum(acc[q]);
      if ((threadIdx.x & 31) == 0 && s != 0.0) atomicAdd(out + 6 * b + q, s);
    }
  }
}

constexpr int kStats = 12;  // the soil statistics' sums (stats_kernel)

template <typename T>
__global__ void stats_kernel(SoilArrays<T> s, long n, double mass, SoilModel<T> model, double* out) {
  // out: ke, px, py, pz, vmax, nonfinite, lost, frozen, mx, my, mz, at the density cap
  double acc[kStats] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  for (long i = blockIdx.x * long(blockDim.x) + threadIdx.x; i < n; i += long(blockDim.x) * gridDim.x) {
    const Vec4<T> v = s.vel[i], p = s.pos[i];
    const double vx = v.x, vy = v.y, vz = v.z;
    const bool finite = isfinite(vx) && isfinite(vy) && isfinite(vz) && isfinite(double(p.x)) &&
                        isfinite(double(p.y)) && isfinite(double(p.z)) && isfinite(double(p.w));
    if (!finite) {
      acc[5] += 1;
      continue;
    }
    if (v.w == T(kParticleLost)) {
      acc[6] += 1;
      continue;
    }
    if (v.w == T(kParticleFrozen))
      acc[7] += 1;
    else if (at_density_cap(p.w, s.s0[i], model))
      acc[11] += 1;
    const double v2 = vx * vx + vy * vy + vz * vz;
    acc[0] += 0.5 * mass * v2;
    acc[1] += mass * vx;
    acc[2] += mass * vy;
    acc[3] += mass * vz;
    acc[4] = fmax(acc[4], sqrt(v2));
    acc[8] += mass * double(p.x);
    acc[9] += mass * double(p.y);
    acc[10] += mass * double(p.z);
  }
  for (int q = 0; q < kStats; ++q) {
    const double r = q == 4 ? warp_max(acc[q]) : warp_sum(acc[q]);
    if ((threadIdx.x & 31) == 0) {
      if (q == 4)
        atomic_max_nonneg(out + 4, r);
      else if (r != 0.0)
        atomicAdd(out + q, r);
    }
  }
}

struct CudaBackend {
  static std::string name() {
    cudaDeviceProp prop{};
    TERRACAL_CUDA_CHECK(cudaGetDeviceProperties(&prop, 0));
    return std::string("CUDA (") + prop.name + ")";
  }
  static std::size_t scratch_bytes() { return cub_scratch().bytes; }
  static void bind(std::size_t particles) { thread_stream().choose(particles < kHighPriorityBelow); }
  // Stream-ordered allocations (the device's memory pool, not managed memory): cudaFree waits for the
  // whole device, and an engine that ended while others ran waited minutes for their kernels.
  template <typename U>
  static U* alloc(std::size_t n) {
    U* p = nullptr;
    TERRACAL_CUDA_CHECK(cudaMallocAsync(reinterpret_cast<void**>(&p), (n > 0 ? n : 1) * sizeof(U), stream()));
    TERRACAL_CUDA_CHECK(cudaMemsetAsync(p, 0, (n > 0 ? n : 1) * sizeof(U), stream()));
    return p;
  }
  template <typename U>
  static void release(U* p) {
    if (p) cudaFreeAsync(p, stream());
  }
  template <typename U>
  static void upload(U* dst, const U* src, std::size_t n) {
    if (!n) return;
    TERRACAL_CUDA_CHECK(cudaMemcpyAsync(dst, src, n * sizeof(U), cudaMemcpyHostToDevice, stream()));
    TERRACAL_CUDA_CHECK(cudaStreamSynchronize(stream()));
  }
  // A small upload (poses, boxes) that does not wait: staged through pinned memory, so that the host
  // goes on queueing the step's launches and the GPU does not drain at every pose.
  template <typename U>
  static void upload_async(U* dst, const U* src, std::size_t n) {
    if (!n) return;
    void* staged = pinned_staging().stage(src, n * sizeof(U));
    if (!staged) return upload(dst, src, n);
    TERRACAL_CUDA_CHECK(cudaMemcpyAsync(dst, staged, n * sizeof(U), cudaMemcpyHostToDevice, stream()));
    pinned_staging().queued(stream());
  }
  template <typename U>
  static void download(U* dst, const U* src, std::size_t n) {
    if (!n) return;
    TERRACAL_CUDA_CHECK(cudaMemcpyAsync(dst, src, n * sizeof(U), cudaMemcpyDeviceToHost, stream()));
    TERRACAL_CUDA_CHECK(cudaStreamSynchronize(stream()));
  }
  template <typename U>
  static void copy(U* dst, const U* src, std::size_t n) {
    if (n) TERRACAL_CUDA_CHECK(cudaMemcpyAsync(dst, src, n * sizeof(U), cudaMemcpyDeviceToDevice, stream()));
  }
  template <typename F>
  static void parallel_for(long n, const F& f) {
    parallel_for_cuda(n, f, stream());
  }
  // The neighbour-loop stages, at the stage's measured best occupancy/register trade-off;
  // TERRACAL_CUDA_MIN_BLOCKS (1-4) overrides it for tuning runs (bench/RESULTS.md).
  static int forced_min_blocks() {
    static const int forced = [] {
      const char* e = std::getenv("TERRACAL_CUDA_MIN_BLOCKS");
      const int v = e ? std::atoi(e) : 0;
      return v >= 1 && v <= 4 ? v : 0;
    }();
    return forced;
  }
  template <typename F>
  static int min_blocks() {
    return forced_min_blocks() ? forced_min_blocks() : PreferredMinBlocks<F>::value;
  }
  static constexpr int kListedMinBlocks = 3;
  // f(std::integral_constant<int, k>) for k = blocks (1-4): the launch bounds are compile-time.
  template <typename F>
  static void with_blocks(int blocks, F&& f) {
    switch (blocks) {
      case 1:
        f(std::integral_constant<int, 1>{});
        break;
      case 2:
        f(std::integral_constant<int, 2>{});
        break;
      case 3:
        f(std::integral_constant<int, 3>{});
        break;
      default:
        f(std::integral_constant<int, 4>{});
        break;
    }
  }
  template <typename F>
  static void parallel_for_heavy(long n, const F& f) {
    with_blocks(min_blocks<F>(), [&](auto k) { parallel_for_cuda_bounded<decltype(k)::value>(n, f, stream()); });
  }
  // The active domain runs its stages over lists of the busy particles and markers (select), so
  // that frozen ones take no thread of the neighbour stages (bench/RESULTS.md, "Active domain").
  static constexpr bool kCompactsActive = true;
  // list[0, *count) = the indices i < n with pred(i), in order; no read-back.
  template <typename Pred>
  static void select(long n, const Pred& pred, int* list, int* count) {
    const thrust::counting_iterator<int> first(0);
    std::size_t bytes = 0;
    TERRACAL_CUDA_CHECK(cub::DeviceSelect::If(nullptr, bytes, first, list, count, n, pred, stream()));
    void* tmp = cub_scratch().ensure(bytes);
    TERRACAL_CUDA_CHECK(cub::DeviceSelect::If(tmp, bytes, first, list, count, n, pred, stream()));
  }
  // f(list[q], group) for q < *count (at most max_items), one wave of blocks. Compiled for 3 blocks
  // per SM (80 registers) unless a stage asks for fewer: the lists are short, registers matter more
  // than occupancy (bench/RESULTS.md, "Active domain on the GPU").
  template <typename F>
  static void parallel_for_listed(const int* list, const int* count, long max_items, const F& f, int lanes) {
    const long sms = cuda_sm_count();
    with_blocks(std::min(min_blocks<F>(), forced_min_blocks() ? 4 : kListedMinBlocks), [&](auto k) {
      constexpr int blocks = decltype(k)::value;
      parallel_for_cuda_listed<blocks>(list, count, max_items, lanes, sms * blocks, f, stream());
    });
  }
  template <typename U>
  static void zero(U* p, std::size_t n) {
    if (n) TERRACAL_CUDA_CHECK(cudaMemsetAsync(p, 0, n * sizeof(U), stream()));
  }

  static void fill_begin(int* begin, int count, int value) {
    parallel_for_cuda(count, FillInt{begin, value}, stream());
  }

  // The markers are sorted from two runs (sph_sort.hpp, MergeMarkerRuns): a sort's passes cost about
  // the same for 5 000 keys as for 70 000, so sorting only the moving bodies' markers pays.
  static constexpr bool kMergesMarkerRuns = true;
  // Sorts in the caller's double buffers (CUB's DoubleBuffer form), so that its scratch holds only
  // its histograms, not another copy of the keys and values; the result is in either buffer.
  static const int* sort_cells(int n, int bins, int* keys, int* vals, int* keys_alt, int* vals_alt, int* begin) {
    const SortedPairs sorted = sort_pairs(n, bins, keys, vals, keys_alt, vals_alt);
    cell_begin(sorted.keys, n, bins, begin);
    return sorted.values;
  }
  // Stable sort of (key, value) pairs by key (keys in [0, bins]) in the caller's double buffers.
  static SortedPairs sort_pairs(int n, int bins, int* keys, int* vals, int* keys_alt, int* vals_alt) {
    int end_bit = 1;
    while ((1 << end_bit) <= bins && end_bit < 31) ++end_bit;
    cub::DoubleBuffer<int> k(keys, keys_alt), v(vals, vals_alt);
    std::size_t bytes = 0;
    TERRACAL_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(nullptr, bytes, k, v, n, 0, end_bit, stream()));
    void* tmp = cub_scratch().ensure(bytes);
    TERRACAL_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(tmp, bytes, k, v, n, 0, end_bit, stream()));
    return {k.Current(), v.Current()};
  }
  // begin[c] for c in [0, bins], from n sorted keys.
  static void cell_begin(const int* keys, int n, int bins, int* begin) {
    parallel_for_cuda(long(bins) + 1, CellBegin{keys, n, begin}, stream());
  }

  template <typename T>
  // out = the bodies' wrenches, then `extra` values that follow them in scratch (a flag), in one copy.
  static void wrench_sum(const MarkerArrays<T>& mk, long nm, const BodyPose<T>* poses, int bodies, double* scratch,
                         double* out, int extra) {
    TERRACAL_CUDA_CHECK(cudaMemsetAsync(scratch, 0, 6 * sizeof(double) * bodies, stream()));
    const int threads = 256;
    const int blocks = int(std::min<long>((nm + threads - 1) / threads, 1024));
    wrench_kernel<<<blocks, threads, 0, stream()>>>(mk, nm, poses, bodies, scratch);
    TERRACAL_CUDA_CHECK(cudaGetLastError());
    download(out, scratch, 6 * std::size_t(bodies) + std::size_t(extra));
  }

  template <typename T>
  static SoilStats soil_stats(const SoilArrays<T>& s, long n, double mass, const SoilModel<T>& model) {
    double* d = reduction_scratch(kStats);
    TERRACAL_CUDA_CHECK(cudaMemsetAsync(d, 0, kStats * sizeof(double), stream()));
    const int threads = 256;
    const int blocks = int(std::max<long>(1, std::min<long>((n + threads - 1) / threads, 2048)));
    stats_kernel<<<blocks, threads, 0, stream()>>>(s, n, mass, model, d);
    TERRACAL_CUDA_CHECK(cudaGetLastError());
    double h[kStats];
    download(h, d, kStats);
    SoilStats st;
    st.kinetic_energy = h[0];
    st.momentum = {h[1], h[2], h[3]};
    st.first_moment = {h[8], h[9], h[10]};
    st.max_speed = h[4];
    st.nonfinite = long(h[5]);
    st.lost = long(h[6]);
    st.frozen = long(h[7]);
    st.at_density_cap = long(h[11]);
    st.mass = mass * double(n - st.lost - st.nonfinite);
    return st;
  }
};

}  // namespace

bool cuda_engine_available(std::string* why) {
  int count = 0;
  const cudaError_t err = cudaGetDeviceCount(&count);
  if (err != cudaSuccess || count == 0) {
    if (why) *why = err == cudaSuccess ? "no CUDA device found" : cudaGetErrorString(err);
    return false;
  }
  return true;
}

std::unique_ptr<SphEngine> make_cuda_engine(const EngineSetup& setup) {
  std::string why;
  if (!cuda_engine_available(&why)) throw RunError("--device cuda: " + why);
  return std::make_unique<SphEngineImpl<float, CudaBackend>>(setup);
}

}  // namespace terracal
