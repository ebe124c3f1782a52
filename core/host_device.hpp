#pragma once
// TERRACAL_HD marks functions that are compiled for both the CPU and the GPU: one physics source,
// two backends (the pbrt-v4 pattern). Without nvcc it expands to nothing.
// TERRACAL_HD_INLINE also makes the compilers inline the function wherever it is called: the terms
// that effects add to a loop body are written apart from it, but belong in it, where the compilers
// can hoist, vectorise and schedule them with the rest.
#if defined(__CUDACC__)
#define TERRACAL_HD __host__ __device__
#define TERRACAL_HD_INLINE __host__ __device__ __forceinline__
#else
#define TERRACAL_HD
#define TERRACAL_HD_INLINE __attribute__((always_inline)) inline
#endif

// Minimum and maximum of two doubles, inlined (std::fmin/fmax are library calls unless NaN handling
// is relaxed). NaN in `a` gives `b`.
TERRACAL_HD_INLINE double min_of(double a, double b) { return a < b ? a : b; }
TERRACAL_HD_INLINE double max_of(double a, double b) { return a > b ? a : b; }
TERRACAL_HD_INLINE double clamp_to(double x, double lo, double hi) { return min_of(max_of(x, lo), hi); }
