#include <catch2/catch.hpp>

#include "core/rng.hpp"

using terracal::Rng;

TEST_CASE("Rng: a restored state continues the exact same sequence", "[core][rng]") {
  Rng a(42);
  for (int i = 0; i < 1000; ++i) a.normal();
  const std::string saved = a.state();
  std::vector<double> expected;
  for (int i = 0; i < 100; ++i) expected.push_back(i % 3 == 0 ? a.normal() : i % 3 == 1 ? a.uniform() : a.gamma(2.5));
  Rng b(7);
  b.set_state(saved);
  for (int i = 0; i < 100; ++i) {
    const double v = i % 3 == 0 ? b.normal() : i % 3 == 1 ? b.uniform() : b.gamma(2.5);
    REQUIRE(v == expected[i]);
  }
}

TEST_CASE("Rng: streams from one seed differ, and the same stream repeats", "[core][rng]") {
  Rng s0 = Rng::for_stream(1, 0), s1 = Rng::for_stream(1, 1), s0b = Rng::for_stream(1, 0);
  const double a = s0.uniform(), b = s1.uniform(), c = s0b.uniform();
  CHECK(a != b);
  CHECK(a == c);
}

TEST_CASE("Rng: normal and gamma moments", "[core][rng]") {
  Rng r(3);
  const int n = 200000;
  double sn = 0, sn2 = 0, sg = 0;
  for (int i = 0; i < n; ++i) {
    const double z = r.normal();
    sn += z;
    sn2 += z * z;
    sg += r.gamma(3.0);
  }
  CHECK(std::abs(sn / n) < 5.0 / std::sqrt(n));
  CHECK(std::abs(sn2 / n - 1.0) < 0.02);
  CHECK(std::abs(sg / n - 3.0) < 5.0 * std::sqrt(3.0 / n));  // Gamma(3,1): mean 3, var 3
}
