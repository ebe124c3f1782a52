#pragma once
// Threads per block of the bounded (register-heavy) GPU launches, parallel_for_cuda_bounded
// (core/parallel_for_cuda.cuh). Here on its own so that device code that keeps per-thread slots in
// shared memory (the soil loop's hit masks, sph_neighbours.hpp) can size them without the launcher.
namespace terracal {
constexpr int kBoundedBlockThreads = 64;
}  // namespace terracal
