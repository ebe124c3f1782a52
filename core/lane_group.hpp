#pragma once
// A group of GPU lanes that share one item of a loop (a particle's neighbour walk): lane k takes rows
// k, k + lanes, ... of the work, so that the lanes run their rows side by side, then the group adds
// up its partial sums with warp shuffles.
// Where few items are busy (an active domain: a few thousand particles of a bed), one thread per item
// leaves the GPU waiting on one thread's walk; a group shortens that walk `lanes`-fold. On the CPU,
// and on the GPU with lanes = 1, the group is one lane and its sums do nothing, so the loop bodies
// that take a group are the same source for both.
#include <type_traits>

#include "core/host_device.hpp"

namespace terracal {

struct LaneGroup {
  int lane = 0;       // this lane's place in its group
  int lanes = 1;      // group size: a power of two that divides 32
  unsigned mask = 1;  // the group's lanes in the warp (for the shuffles)

  TERRACAL_HD bool leader() const { return lane == 0; }

  // x = the sum of x over the group, on every lane. X is a plain struct of T (sums of a neighbour
  // loop). The butterfly adds the same pairs in the same order on every lane, so all lanes end with
  // the same bits.
  template <typename T, typename X>
  TERRACAL_HD void sum(X& x) const {
#if defined(__CUDA_ARCH__)
    static_assert(std::is_trivially_copyable_v<X>);
    constexpr int kCount = int(sizeof(X) / sizeof(T));
    if constexpr (kCount > 0 && sizeof(X) % sizeof(T) == 0) {
      if (lanes == 1) return;
      T* p = reinterpret_cast<T*>(&x);
#pragma unroll
      for (int q = 0; q < kCount; ++q)
        for (int o = lanes >> 1; o > 0; o >>= 1) p[q] += __shfl_xor_sync(mask, p[q], o);
    }
#else
    (void)x;
#endif
  }

  // v = the least v over the group, on every lane.
  template <typename T>
  TERRACAL_HD void min(T& v) const {
#if defined(__CUDA_ARCH__)
    for (int o = lanes >> 1; o > 0; o >>= 1) {
      const T w = __shfl_xor_sync(mask, v, o);
      v = w < v ? w : v;
    }
#else
    (void)v;
#endif
  }
};

// One lane: what the plain loops take, so that their code has no shuffles and no sums whose
// address is taken (which would put them in local memory).
struct SingleLane {
  static constexpr int lane = 0;
  static constexpr int lanes = 1;
  TERRACAL_HD static constexpr bool leader() { return true; }
  template <typename T, typename X>
  TERRACAL_HD static void sum(X&) {}
  template <typename T>
  TERRACAL_HD static void min(T&) {}
};

#if defined(__CUDACC__)
// The group of the calling thread, for groups of `lanes` consecutive threads.
__device__ inline LaneGroup lane_group_of(long thread, int lanes) {
  LaneGroup g;
  g.lanes = lanes;
  g.lane = int(thread % lanes);
  const unsigned bits = lanes >= 32 ? 0xffffffffu : ((1u << lanes) - 1u);
  g.mask = bits << ((threadIdx.x & 31u) & ~unsigned(lanes - 1));
  return g;
}
#endif

}  // namespace terracal
