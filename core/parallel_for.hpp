#pragma once
// pbrt-v4's pattern: physics is written once as a host/device functor f(i); backends differ only
// in how they loop over i. This header is the CPU loop (OpenMP); parallel_for_cuda.cuh the GPU one.
namespace terracal {

template <typename F>
void parallel_for_cpu(long n, const F& f) {
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) f(i);
}

// For loops whose iterations differ in cost (particles with more or fewer neighbours, markers
// with or without soil around them): chunks are handed out as threads free up.
template <typename F>
void parallel_for_cpu_balanced(long n, const F& f) {
#pragma omp parallel for schedule(dynamic, 512)
  for (long i = 0; i < n; ++i) f(i);
}

}  // namespace terracal
