#pragma once
// The GPU loop of parallel_for: a grid-stride kernel over a host/device functor. Compiled by nvcc only.
#include <algorithm>

#include "core/cuda_check.hpp"

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

// For register-heavy functors: __launch_bounds__ asks the compiler to fit `MinBlocks` blocks of 256
// threads per SM (more warps in flight to hide memory latency, at the price of fewer registers).
template <int MinBlocks, typename F>
__global__ void __launch_bounds__(256, MinBlocks) bounded_parallel_for_kernel(long n, F f) {
  for (long i = blockIdx.x * long(blockDim.x) + threadIdx.x; i < n; i += long(blockDim.x) * gridDim.x) f(i);
}

template <int MinBlocks, typename F>
void parallel_for_cuda_bounded(long n, const F& f) {
  if (n <= 0) return;
  constexpr int kThreads = 256;
  const long blocks = std::min<long>((n + kThreads - 1) / kThreads, 65535L * 8);
  bounded_parallel_for_kernel<MinBlocks><<<static_cast<unsigned>(blocks), kThreads>>>(n, f);
  TERRACAL_CUDA_CHECK(cudaGetLastError());
}

}  // namespace terracal
