#pragma once
// The smallest end-to-end use of the GPU backend: y <- a x + y from one host/device functor, run
// by the CPU loop and by the CUDA loop. Its test proves in CI that the CUDA path compiles and
// links; on a machine with a GPU it checks that both backends compute the same numbers.
#include <string>
#include <vector>

#include "core/host_device.hpp"

namespace terracal {

struct Axpy {
  double a;
  const double* x;
  double* y;
  TERRACAL_HD void operator()(long i) const { y[i] = a * x[i] + y[i]; }
};

struct CudaDeviceInfo {
  bool available = false;
  std::string description;  // device name and compute capability, or why there is none
  int count = 0;            // devices present
};

// Whether this build has CUDA and a device is present.
CudaDeviceInfo cuda_device_info();

void axpy_cpu(double a, const std::vector<double>& x, std::vector<double>& y);
// Throws RunError if this build has no CUDA or no device is present (check cuda_device_info first).
void axpy_cuda(double a, const std::vector<double>& x, std::vector<double>& y);

}  // namespace terracal
