// The GPU test with its CPU twin. The CPU twin always runs; the GPU half runs when a device is
// present and says clearly that it skipped otherwise.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "core/device_selftest.hpp"
#include "core/rng.hpp"
#include "tests/skip.hpp"

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
  if (!test::cuda_device_or_skip("device self-test: CUDA and CPU agree")) return;
  const CudaDeviceInfo info = cuda_device_info();
  INFO("device: " << info.description);
  std::vector<double> x(1 << 20), y(1 << 20);
  random_inputs(x, y, 6);
  const std::vector<double> y0 = y;
  std::vector<double> y_cpu = y, y_gpu = y;
  axpy_cpu(-1.75, x, y_cpu);
  axpy_cuda(-1.75, x, y_gpu);
  double max_rel = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    REQUIRE(std::isfinite(y_gpu[i]));
    // Relative to the size of the terms, not of the result: where a x ~ -y the sum cancels and
    // the GPU's fused multiply-add (one rounding instead of two) differs by an ulp of the terms.
    max_rel = std::max(max_rel, std::abs(y_gpu[i] - y_cpu[i]) / (std::abs(1.75 * x[i]) + std::abs(y0[i])));
  }
  INFO("max difference relative to |a x| + |y|: " << max_rel);
  CHECK(max_rel < 4e-16);
}
