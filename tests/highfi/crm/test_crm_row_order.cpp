// The GPU soil loop takes a particle's neighbour rows in pairs opposite each other about its cell and
// sums the hits of several rows in one loop (for_each_hit_in_phases, sph_neighbours.hpp). Its row
// order (GridGeometry::for_each_row_in_opposite_pairs) must name every row of the (2 reach + 1)^2
// block exactly once, number them 0, 1, ... in the order given, put the two rows of each pair opposite
// each other and end with the particle's own row. The CUDA stage that uses it is checked against the
// CPU's by "CRM: CUDA and CPU agree over 200 steps" (test_crm_cpu_gpu.cpp).
#include <catch2/catch.hpp>

#include <cstdlib>
#include <set>
#include <utility>
#include <vector>

#include "highfi/crm/sph_fields.hpp"

using namespace terracal;

TEST_CASE("CRM grid: the rows in opposite pairs name every neighbour row once", "[crm]") {
  for (int reach = 1; reach <= 3; ++reach) {
    GridGeometry<float> grid;
    grid.reach = reach;
    std::vector<std::pair<int, int>> rows;
    int expected_k = 0;
    grid.for_each_row_in_opposite_pairs([&](int dy, int dz, int k) {
      CHECK(k == expected_k);
      ++expected_k;
      rows.emplace_back(dy, dz);
    });
    const int side = 2 * reach + 1;
    REQUIRE(int(rows.size()) == side * side);
    const std::set<std::pair<int, int>> distinct(rows.begin(), rows.end());
    CHECK(int(distinct.size()) == side * side);
    for (const auto& [dy, dz] : rows) {
      CHECK(std::abs(dy) <= reach);
      CHECK(std::abs(dz) <= reach);
    }
    for (std::size_t p = 0; p + 1 < rows.size(); p += 2) {
      CHECK(rows[p].first == -rows[p + 1].first);
      CHECK(rows[p].second == -rows[p + 1].second);
      CHECK(rows[p] != rows[p + 1]);
    }
    CHECK(rows.back() == std::make_pair(0, 0));
  }
}
