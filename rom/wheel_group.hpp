#pragma once
// The lanes that share one vehicle's four wheels. On the CPU (and for the single-track model) one
// lane takes every wheel. On the GPU four consecutive lanes of a warp step one vehicle: each lane
// keeps the whole state, runs the chassis' arithmetic as the others do (the same bits), and computes
// only its own wheel's tire; the four contacts are then exchanged with warp shuffles. A GPU batch
// waits on one thread's chain of dependent double-precision operations per step, and the tires are
// most of it: four lanes side by side issue the tires once instead of four times.
#include "core/host_device.hpp"

namespace terracal::rom {

template <int N>
struct WheelGroup {
  static_assert(N == 1 || N == 4, "one lane per vehicle, or one per wheel");
  static constexpr int kLanes = N;
  static constexpr int kSlots = 4 / N;  // wheels per lane
  int lane = 0;                         // this lane's wheel (N = 4)
  unsigned mask = 0xfu;                 // the group's lanes in the warp (N = 4)

  TERRACAL_HD bool leader() const { return N == 1 || lane == 0; }
  // The wheel in this lane's slot j.
  TERRACAL_HD int wheel(int j) const { return N == 1 ? j : lane + j * N; }
  // a[w] of a per-wheel array in registers: selects, not an indexed load, where w is this lane's
  // (an indexed load would move the array to local memory).
  TERRACAL_HD static double of_wheel(const double* a, int w) {
    if constexpr (N == 1) {
      return a[w];
    } else {
      return w == 0 ? a[0] : w == 1 ? a[1] : w == 2 ? a[2] : a[3];
    }
  }
  // x as the lane of wheel w has it.
  TERRACAL_HD double from_wheel(double x, int w) const {
#if defined(__CUDA_ARCH__)
    if constexpr (N > 1) return __shfl_sync(mask, x, w, N);
#endif
    (void)w;
    return x;
  }
};

using OneLanePerVehicle = WheelGroup<1>;

#if defined(__CUDACC__)
// The group of GPU thread t: vehicle t / N, wheel t % N (groups of N consecutive lanes).
template <int N>
__device__ inline WheelGroup<N> wheel_group_of(long t) {
  WheelGroup<N> g;
  g.lane = int(t % N);
  g.mask = (N == 1 ? 1u : 0xfu) << ((threadIdx.x & 31u) & ~unsigned(N - 1));
  return g;
}
#endif

}  // namespace terracal::rom
