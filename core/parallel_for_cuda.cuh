#pragma once
// The GPU loop of parallel_for: a grid-stride kernel over a host/device functor. Compiled by nvcc only.
#include <algorithm>

#include "core/cuda_check.hpp"
#include "core/lane_group.hpp"

namespace terracal {

template <typename F>
__global__ void parallel_for_kernel(long n, F f) {
  for (long i = blockIdx.x * long(blockDim.x) + threadIdx.x; i < n; i += long(blockDim.x) * gridDim.x) f(i);
}

template <typename F>
void parallel_for_cuda(long n, const F& f, cudaStream_t stream = nullptr) {
  if (n <= 0) return;
  constexpr int kThreads = 256;
  const long blocks = std::min<long>((n + kThreads - 1) / kThreads, 65535L * 8);
  parallel_for_kernel<<<static_cast<unsigned>(blocks), kThreads, 0, stream>>>(n, f);
  TERRACAL_CUDA_CHECK(cudaGetLastError());
}

// The current device's multiprocessors (asked once).
inline int cuda_sm_count() {
  static const int sms = [] {
    int device = 0, count = 0;
    TERRACAL_CUDA_CHECK(cudaGetDevice(&device));
    TERRACAL_CUDA_CHECK(cudaDeviceGetAttribute(&count, cudaDevAttrMultiProcessorCount, device));
    return std::max(count, 1);
  }();
  return sms;
}

// For loops of few long iterations (a ROM batch: one thread steps one vehicle through thousands of
// steps), whose time is one thread's latency, not throughput: blocks small enough (down to one warp)
// that every SM gets a share, instead of 256-thread blocks that pile a few thousand threads onto a
// quarter of the SMs.
inline int spread_block_threads(long n) {
  const int sms = cuda_sm_count();
  const long per_sm = (n + sms - 1) / sms;
  return static_cast<int>(std::clamp<long>((per_sm + 31) / 32 * 32, 32, 256));
}

template <typename F>
void parallel_for_cuda_spread(long n, const F& f) {
  if (n <= 0) return;
  const int threads = spread_block_threads(n);
  const long blocks = std::min<long>((n + threads - 1) / threads, 65535L * 8);
  parallel_for_kernel<<<static_cast<unsigned>(blocks), threads>>>(n, f);
  TERRACAL_CUDA_CHECK(cudaGetLastError());
}

// Whether parallel_for_cuda_spread(n, F) runs all its blocks at once (one wave): then the loop lasts
// one thread's time, and more threads per item shorten it; past one wave they queue.
template <typename F>
bool spread_fits_one_wave(long n) {
  const int threads = spread_block_threads(n);
  int per_sm = 0;
  TERRACAL_CUDA_CHECK(cudaOccupancyMaxActiveBlocksPerMultiprocessor(&per_sm, parallel_for_kernel<F>, threads, 0));
  return (n + threads - 1) / threads <= long(per_sm) * cuda_sm_count();
}

// For register-heavy functors: __launch_bounds__ asks the compiler to fit `MinBlocks` blocks of 256
// threads per SM (more warps in flight to hide memory latency, at the price of fewer registers).
// The launches use blocks of kBoundedBlockThreads with the same registers per thread: an SM takes a
// new block only once every warp of one has finished, and the items' work differs (a particle's
// neighbours), so small blocks keep more warps busy (docs/decisions.md, "CUDA launch bounds").
constexpr int kBoundedBlockThreads = 64;
template <int MinBlocks, typename F>
__global__ void __launch_bounds__(kBoundedBlockThreads, MinBlocks * 256 / kBoundedBlockThreads)
    bounded_parallel_for_kernel(long n, F f) {
  for (long i = blockIdx.x * long(blockDim.x) + threadIdx.x; i < n; i += long(blockDim.x) * gridDim.x) f(i);
}

template <int MinBlocks, typename F>
void parallel_for_cuda_bounded(long n, const F& f, cudaStream_t stream = nullptr) {
  if (n <= 0) return;
  constexpr int kThreads = kBoundedBlockThreads;
  const long blocks = std::min<long>((n + kThreads - 1) / kThreads, 65535L * 8);
  bounded_parallel_for_kernel<MinBlocks><<<static_cast<unsigned>(blocks), kThreads, 0, stream>>>(n, f);
  TERRACAL_CUDA_CHECK(cudaGetLastError());
}

// Groups of `lanes` threads over the items list[0, *count): a list made on the device (an active
// domain's particles) is run without reading its length back. One wave of `blocks` blocks strides
// over it.
template <int MinBlocks, typename F>
__global__ void __launch_bounds__(256, MinBlocks)
    listed_parallel_for_kernel(const int* list, const int* count, int lanes, F f) {
  const long total = long(*count) * lanes;
  for (long t = blockIdx.x * long(blockDim.x) + threadIdx.x; t < total; t += long(blockDim.x) * gridDim.x)
    f(list[t / lanes], lane_group_of(t, lanes));
}

template <int MinBlocks, typename F>
void parallel_for_cuda_listed(const int* list, const int* count, long max_items, int lanes, long max_blocks, const F& f,
                              cudaStream_t stream = nullptr) {
  if (max_items <= 0) return;
  constexpr int kThreads = 256;
  const long blocks = std::max<long>(1, std::min<long>((max_items * lanes + kThreads - 1) / kThreads, max_blocks));
  listed_parallel_for_kernel<MinBlocks><<<static_cast<unsigned>(blocks), kThreads, 0, stream>>>(list, count, lanes, f);
  TERRACAL_CUDA_CHECK(cudaGetLastError());
}

}  // namespace terracal
