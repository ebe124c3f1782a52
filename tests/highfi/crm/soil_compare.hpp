#pragma once
// Comparing two CRM runs' soil particle by particle: the engines keep the particles sorted by cell,
// so two runs whose sums differ at round-off may hold them in different orders; they are matched by id.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "highfi/crm/sph_engine.hpp"

namespace terracal::test {

// The largest difference of one particle's position between the two soils, per axis.
inline double largest_position_difference(const HostSoil& a, const HostSoil& b) {
  REQUIRE(a.size() == b.size());
  std::vector<long> at(a.size(), -1);
  for (std::size_t i = 0; i < b.size(); ++i) at[std::size_t(b.ids[i])] = long(i);
  double worst = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const long q = at[std::size_t(a.ids[i])];
    REQUIRE(q >= 0);
    const Vec4<double> x = a.pos[i], y = b.pos[std::size_t(q)];
    worst = std::max({worst, std::abs(x.x - y.x), std::abs(x.y - y.y), std::abs(x.z - y.z)});
  }
  return worst;
}

}  // namespace terracal::test
