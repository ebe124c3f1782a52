// The CUDA half of the device self-test: the same Axpy functor as the CPU loop.
#include <fmt/format.h>

#include "core/device_selftest.hpp"
#include "core/parallel_for_cuda.cuh"

namespace terracal {

CudaDeviceInfo cuda_device_info() {
  int count = 0;
  const cudaError_t err = cudaGetDeviceCount(&count);
  if (err != cudaSuccess || count == 0)
    return {false, fmt::format("no CUDA device ({})", err == cudaSuccess ? "none found" : cudaGetErrorString(err))};
  cudaDeviceProp prop{};
  TERRACAL_CUDA_CHECK(cudaGetDeviceProperties(&prop, 0));
  return {true,
          fmt::format("{} (sm_{}{}, {:.1f} GiB)", prop.name, prop.major, prop.minor, prop.totalGlobalMem / 1073741824.0),
          count};
}

namespace {
// Device buffers freed on every path, including a thrown CUDA error.
struct DeviceBuffer {
  double* p = nullptr;
  explicit DeviceBuffer(std::size_t n) { TERRACAL_CUDA_CHECK(cudaMalloc(&p, n * sizeof(double))); }
  ~DeviceBuffer() { cudaFree(p); }
};
}  // namespace

void axpy_cuda(double a, const std::vector<double>& x, std::vector<double>& y) {
  if (!cuda_device_info().available) throw RunError("axpy_cuda: no CUDA device");
  const std::size_t n = x.size();
  DeviceBuffer dx(n), dy(n);
  TERRACAL_CUDA_CHECK(cudaMemcpy(dx.p, x.data(), n * sizeof(double), cudaMemcpyHostToDevice));
  TERRACAL_CUDA_CHECK(cudaMemcpy(dy.p, y.data(), n * sizeof(double), cudaMemcpyHostToDevice));
  parallel_for_cuda(static_cast<long>(n), Axpy{a, dx.p, dy.p});
  TERRACAL_CUDA_CHECK(cudaDeviceSynchronize());
  TERRACAL_CUDA_CHECK(cudaMemcpy(y.data(), dy.p, n * sizeof(double), cudaMemcpyDeviceToHost));
}

}  // namespace terracal
