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
