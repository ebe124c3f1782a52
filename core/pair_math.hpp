#pragma once
// Division and square root for the terms of a pair of particles, the CRM neighbour loops' hot path.
// On the GPU, in float32, they are the hardware's approximations (at most 2 ulp; a rounding error of
// the order of float32's own): IEEE division and square root are subroutines with slow paths, whose
// call sites cost the soil stage 15 % of its instructions and its registers (spills to local memory),
// and the rigs' configuration ran 1.18x slower with them (docs/decisions.md, "Pair arithmetic on the
// GPU"). The CPU, and double precision everywhere, keep IEEE operations, so the CPU's results do not
// change.
#include <cmath>
#include <type_traits>

#include "core/host_device.hpp"

namespace terracal {

// a / b.
template <typename T>
TERRACAL_HD_INLINE T pair_div(T a, T b) {
#if defined(__CUDA_ARCH__)
  if constexpr (std::is_same_v<T, float>) {
    return __fdividef(a, b);
  } else {
    return a / b;
  }
#else
  return a / b;
#endif
}

// sqrt(x) for x >= 0 (0 gives 0).
template <typename T>
TERRACAL_HD_INLINE T pair_sqrt(T x) {
#if defined(__CUDA_ARCH__)
  if constexpr (std::is_same_v<T, float>) {
    return x > 0.0f ? x * rsqrtf(x) : 0.0f;
  } else {
    return std::sqrt(x);
  }
#else
  return std::sqrt(x);
#endif
}

}  // namespace terracal
