// The GPU test with its CPU twin. The CPU twin always runs; the GPU half runs when a device is
// present and says clearly that it skipped otherwise.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "core/device_selftest.hpp"
#include "core/rng.hpp"

using namespace terracal;

namespace {
void random_inputs(std::vector<double>& x, std::vector<double>& y, std::uint64_t seed) {
  Rng rng(seed);
  for (auto& v : x) v = rng.normal();
  for (auto& v : y) v = rng.normal();
}
}  // namespace

TEST_CASE("device self-test: the CPU loop computes a x + y", "[core][device]") {
  std::vector<double> x(100001), y(100001);
  random_inputs(x, y, 5);
  const std::vector<double> y0 = y;
  axpy_cpu(2.5, x, y);
  for (std::size_t i = 0; i < x.size(); ++i) REQUIRE(y[i] == 2.5 * x[i] + y0[i]);
}

TEST_CASE("device self-test: CUDA and CPU agree", "[core][device][gpu]") {
  const CudaDeviceInfo info = cuda_device_info();
  if (!info.available) {
    std::fprintf(stderr, "SKIPPED: GPU test 'CUDA and CPU agree': %s\n", info.description.c_str());
    WARN("GPU test skipped: " << info.description);
    return;
  }
  INFO("device: " << info.description);
  std::vector<double> x(1 << 20), y(1 << 20);
  random_inputs(x, y, 6);
  std::vector<double> y_cpu = y, y_gpu = y;
  axpy_cpu(-1.75, x, y_cpu);
  axpy_cuda(-1.75, x, y_gpu);
  double max_rel = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    REQUIRE(std::isfinite(y_gpu[i]));
    max_rel = std::max(max_rel, std::abs(y_gpu[i] - y_cpu[i]) / std::max(1e-300, std::abs(y_cpu[i])));
  }
  // The GPU may fuse the multiply-add (one rounding instead of two): agreement to a few ulps.
  CHECK(max_rel < 1e-12);
}
