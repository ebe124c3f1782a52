#include "core/device_selftest.hpp"

#include "core/errors.hpp"
#include "core/parallel_for.hpp"

namespace terracal {

void axpy_cpu(double a, const std::vector<double>& x, std::vector<double>& y) {
  parallel_for_cpu(static_cast<long>(x.size()), Axpy{a, x.data(), y.data()});
}

#ifndef TERRACAL_HAVE_CUDA
// A build without nvcc: the GPU entry points exist and say why they cannot run.
CudaDeviceInfo cuda_device_info() {
  return {false, "this build has no CUDA backend (nvcc not found at configure time)"};
}
void axpy_cuda(double, const std::vector<double>&, std::vector<double>&) {
  throw RunError("axpy_cuda: this build has no CUDA backend");
}
#endif

}  // namespace terracal
