// The CPU's SIMD neighbour filter and staging must reproduce their scalar definitions exactly:
// the same set of neighbours (the vector filter may list them in another order) and, for every
// list length, the same staged records in list order.
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>
#include <vector>

#include "highfi/crm/neighbour_filter_cpu.hpp"

using namespace terracal;

// Without AVX2 (TERRACAL_CPU_ARCH=OFF or an older CPU) the solver runs the scalar path and these
// tests compare it with itself; they say so rather than pass silently.
#if defined(__AVX2__)
#define TERRACAL_NOTE_SCALAR_ONLY()
#else
#define TERRACAL_NOTE_SCALAR_ONLY() WARN("built without AVX2: the SIMD path is the scalar one here")
#endif

TEST_CASE("CPU neighbour filter: SIMD and scalar list the same neighbours", "[highfi][crm]") {
  TERRACAL_NOTE_SCALAR_ONLY();
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  std::vector<Vec4<float>> pos(300 + 8);
  for (auto& p : pos) p = {u(rng), u(rng), u(rng), 1.f};
  const Vec3<float> x{0.1f, -0.2f, 0.05f};
  for (int first : {0, 3, 17}) {
    for (int len : {0, 1, 7, 8, 9, 31, 200}) {
      const int last = first + len;
      std::vector<int> a(len + 8), b(len + 8);
      const int na = filter_row(pos.data(), first, last, long(first + 2), x, 0.5f, a.data(), 0);
      const int nb = filter_row_scalar(pos.data(), first, last, long(first + 2), x, 0.5f, b.data(), 0);
      REQUIRE(na == nb);
      std::sort(a.begin(), a.begin() + na);
      CHECK(std::equal(a.begin(), a.begin() + na, b.begin()));
      if (len > 2) CHECK(std::find(a.begin(), a.begin() + na, first + 2) == a.begin() + na);  // self excluded
    }
  }
}

TEST_CASE("CPU neighbour staging: SIMD and scalar stage the same records in list order", "[highfi][crm]") {
  TERRACAL_NOTE_SCALAR_ONLY();
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  const int records = 100;
  std::vector<Vec4<float>> f[4];
  for (auto& a : f) {
    a.resize(records);
    for (auto& r : a) r = {u(rng), u(rng), u(rng), u(rng)};
  }
  for (int n : {1, 3, 5, 8, 13, 64}) {
    std::vector<int> list(n + 8);
    for (int q = 0; q < n; ++q) list[q] = int(rng() % records);
    std::vector<float> a(kStagedFields * (n + 8)), b(kStagedFields * (n + 8));
    float* pa[kStagedFields];
    float* pb[kStagedFields];
    for (int c = 0; c < kStagedFields; ++c) {
      pa[c] = a.data() + c * (n + 8);
      pb[c] = b.data() + c * (n + 8);
    }
    stage_neighbours(f[0].data(), f[1].data(), f[2].data(), f[3].data(), list.data(), n, pa);
    stage_neighbours_scalar(f[0].data(), f[1].data(), f[2].data(), f[3].data(), list.data(), n, pb);
    for (int c = 0; c < kStagedFields; ++c) CHECK(std::equal(pa[c], pa[c] + n, pb[c]));
  }
}
