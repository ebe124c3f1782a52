// The GPU soil loop walks a particle's neighbour rows in pairs opposite each other about its cell
// (GridGeometry::for_each_neighbour_row_pair), so that a warp sums two rows' hits in one loop. The
// pairs must hand over every row that the plain walk (for_each_neighbour_range) visits, each once, for
// a particle anywhere in the grid (edges and corners included) and for every lane group; and the two
// rows of a pair must lie opposite each other. The CUDA stage that uses it is checked against the CPU
// by "CRM: CUDA and CPU agree over 200 steps" (test_crm_cpu_gpu.cpp).
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>
#include <utility>
#include <vector>

#include "highfi/crm/sph_fields.hpp"

using namespace terracal;

namespace {

// A particle's rows as the plain walk and as the pairs hand them over, each row as (first, last), and
// the pairs' rows as cell offsets (dy, dz) from the particle's cell.
struct Walks {
  std::vector<std::pair<int, int>> plain, paired;
  std::vector<std::pair<std::pair<int, int>, std::pair<int, int>>> pair_offsets;
};

// begin[] that gives every row of cells its own range, so that a range names its row: the cell
// (x, y, z) starts at 1000 * (row index) + x.
std::vector<int> row_naming_begin(const GridGeometry<float>& grid) {
  std::vector<int> begin(grid.cells() + 1);
  for (int c = 0; c <= grid.cells(); ++c) begin[c] = 1000 * (c / grid.nx) + c % grid.nx;
  return begin;
}

Walks walks(const GridGeometry<float>& grid, const std::vector<int>& begin, const Vec3<float>& p, int lanes) {
  Walks w;
  grid.for_each_neighbour_range(p, begin.data(), [&](int first, int last) { w.plain.emplace_back(first, last); });
  int ix = 0, iy = 0, iz = 0;
  REQUIRE(grid.cell_coords(p, ix, iy, iz));
  auto offset = [&](int first) {
    const int row = first / 1000;
    return std::make_pair(row % grid.ny - iy, row / grid.ny - iz);
  };
  for (int lane = 0; lane < lanes; ++lane) {
    LaneGroup g;
    g.lane = lane;
    g.lanes = lanes;
    grid.for_each_neighbour_row_pair(p, begin.data(), g, [&](int a, int ae, int b, int be) {
      if (a < ae) w.paired.emplace_back(a, ae);
      if (b < be) w.paired.emplace_back(b, be);
      if (a < ae && b < be) w.pair_offsets.push_back({offset(a), offset(b)});
    });
  }
  return w;
}

}  // namespace

TEST_CASE("CRM GPU loop: the row pairs visit every neighbour row once, in opposite pairs", "[highfi][crm]") {
  for (const int reach : {1, 2, 3}) {
    const GridGeometry<float> grid{{0.f, 0.f, 0.f}, 1.f / 0.05f, 9, 8, 7, reach};
    const std::vector<int> begin = row_naming_begin(grid);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> x(0.f, 0.45f), y(0.f, 0.4f), z(0.f, 0.35f);
    int pairs_checked = 0;
    for (int trial = 0; trial < 400; ++trial) {
      Vec3<float> p{x(rng), y(rng), z(rng)};
      if (trial < 8) p = {trial & 1 ? 0.449f : 0.f, trial & 2 ? 0.399f : 0.f, trial & 4 ? 0.349f : 0.f};  // corners
      for (const int lanes : {1, 2, 8, 32}) {
        Walks w = walks(grid, begin, p, lanes);
        // The plain walk hands over empty rows too; the pairs leave them out.
        w.plain.erase(std::remove_if(w.plain.begin(), w.plain.end(), [](auto r) { return r.first >= r.second; }),
                      w.plain.end());
        std::sort(w.plain.begin(), w.plain.end());
        std::sort(w.paired.begin(), w.paired.end());
        INFO("reach " << reach << ", lanes " << lanes << ", p = (" << p.x << ", " << p.y << ", " << p.z << ")");
        REQUIRE(!w.plain.empty());
        CHECK(w.paired == w.plain);
        for (const auto& [a, b] : w.pair_offsets) {
          CHECK(a.first == -b.first);
          CHECK(a.second == -b.second);
          ++pairs_checked;
        }
      }
    }
    CHECK(pairs_checked > 1000);
  }
}

TEST_CASE("CRM GPU loop: a particle outside the grid has no row pairs", "[highfi][crm]") {
  const GridGeometry<float> grid{{0.f, 0.f, 0.f}, 1.f / 0.05f, 9, 8, 7, 2};
  const std::vector<int> begin = row_naming_begin(grid);
  int calls = 0;
  grid.for_each_neighbour_row_pair(Vec3<float>{-0.01f, 0.1f, 0.1f}, begin.data(), SingleLane{},
                                   [&](int, int, int, int) { ++calls; });
  CHECK(calls == 0);
}
