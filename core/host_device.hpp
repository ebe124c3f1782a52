#pragma once
// TERRACAL_HD marks functions that are compiled for both the CPU and the GPU: one physics source,
// two backends (the pbrt-v4 pattern). Without nvcc it expands to nothing.
#if defined(__CUDACC__)
#define TERRACAL_HD __host__ __device__
#else
#define TERRACAL_HD
#endif
