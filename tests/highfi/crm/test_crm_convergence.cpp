// Validation 9: resolution convergence of the plate force. A 0.1 m-radius plate pushed into the
// bed, force at 2 cm sinkage, at three spacings refined by sqrt(2): the differences between
// successive spacings must shrink and the two finest must agree within 10 %. The CPU twin runs in
// CI at 2, 1.4 and 1 cm in a 0.4 m bin; the GPU runs 1, 0.7 and 0.5 cm in a 0.5 m bin.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <string>

#include "tests/highfi/crm/crm_plate_study.hpp"
#include "tests/skip.hpp"

using namespace terracal;

namespace {

void check_convergence(const std::vector<double>& spacings, const test::PlateBin& bin, CrmDevice device) {
  std::vector<test::PlateForce> f;
  for (double d0 : spacings) f.push_back(test::plate_force_at_2cm(d0, bin, device));
  const double d01 = std::abs(f[1].force - f[0].force), d12 = std::abs(f[2].force - f[1].force);
  const double rel = d12 / std::abs(f[2].force);
  std::printf("plate convergence: |F2-F1| = %.2f N, |F3-F2| = %.2f N, finest two differ by %.1f %%\n", d01, d12,
              100 * rel);
  for (const auto& x : f) CHECK(x.force > 0);
  CHECK(d12 < d01);
  CHECK(rel < 0.10);
}

}  // namespace

TEST_CASE("CRM: plate force converges with resolution on the CPU", "[highfi][crm]") {
  test::PlateBin bin;
  bin.side = 0.4;
  bin.depth = 0.15;
  check_convergence({0.02, 0.02 / std::sqrt(2.0), 0.01}, bin, CrmDevice::kCpu);
}

TEST_CASE("CRM: plate force converges with resolution on the GPU", "[highfi][crm][device][gpu]") {
  if (!test::cuda_device_or_skip("CRM: plate force converges with resolution on the GPU")) return;
  test::PlateBin bin;
  bin.side = 0.5;
  bin.depth = 0.2;
  check_convergence({0.01, 0.01 / std::sqrt(2.0), 0.005}, bin, CrmDevice::kCuda);
}
