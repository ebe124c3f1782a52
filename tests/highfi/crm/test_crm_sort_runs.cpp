// The markers' sort by cell from two runs (MergeMarkerRuns, sph_sort.hpp): the fixed markers sorted
// once, the moving ones at every pose. Its order must be the stable sort of every marker by cell to the
// last index, which is what keeps a run's sums as they were and a restarted run's the same as one that
// went on.
#include <catch2/catch.hpp>

#include <algorithm>
#include <numeric>
#include <random>
#include <vector>

#include "highfi/crm/sph_sort.hpp"

using namespace terracal;

namespace {

// The reference: every marker stably sorted by its cell.
std::vector<int> stable_order(const std::vector<int>& keys) {
  std::vector<int> order(keys.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return keys[a] < keys[b]; });
  return order;
}

// A run sorted by (cell, index), as the backends' stable sort of an ascending index list leaves it.
void sort_run(std::vector<int>& index, const std::vector<int>& keys) {
  std::stable_sort(index.begin(), index.end(), [&](int a, int b) { return keys[a] < keys[b]; });
}

}  // namespace

TEST_CASE("CRM markers: the two-run merge gives the stable sort of every marker by cell", "[highfi][crm]") {
  GridGeometry<float> grid{{0.f, 0.f, 0.f}, 1.f / 0.05f, 12, 9, 7, 2};
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> x(-0.05f, 0.65f), y(-0.05f, 0.5f), z(-0.05f, 0.4f);
  for (const double moving_share : {0.02, 0.3, 0.5}) {
    const int n = 5000;
    std::vector<Vec4<float>> pos(n);
    for (auto& p : pos) p = {x(rng), y(rng), z(rng), 1.f};  // some outside the grid: the last bin
    // Markers crowd into few cells, so that many ties are broken by index.
    for (int m = 0; m < n; m += 3) pos[m] = pos[(m * 7) % 40];
    std::vector<int> fixed, moving;
    std::bernoulli_distribution is_moving(moving_share);
    for (int m = 0; m < n; ++m) (is_moving(rng) ? moving : fixed).push_back(m);

    std::vector<int> keys(n), values(n), all(n);
    std::iota(all.begin(), all.end(), 0);
    const MarkerSubsetCellKey<float> key_of{grid, pos.data(), all.data(), keys.data(), values.data()};
    for (int m = 0; m < n; ++m) key_of(m);
    CHECK(values == all);
    CHECK(std::count(keys.begin(), keys.end(), grid.cells()) > 0);

    sort_run(fixed, keys);
    sort_run(moving, keys);
    std::vector<int> moving_keys(moving.size());
    for (std::size_t j = 0; j < moving.size(); ++j) moving_keys[j] = keys[std::size_t(moving[j])];

    std::vector<int> merged_keys(n, -1), perm(n, -1);
    const MergeMarkerRuns<float> merge{grid,
                                       pos.data(),
                                       fixed.data(),
                                       int(fixed.size()),
                                       moving_keys.data(),
                                       moving.data(),
                                       int(moving.size()),
                                       merged_keys.data(),
                                       perm.data()};
    for (int i = 0; i < n; ++i) merge(i);

    const std::vector<int> expected = stable_order(keys);
    CHECK(perm == expected);
    for (int i = 0; i < n; ++i) CHECK(merged_keys[i] == keys[std::size_t(expected[std::size_t(i)])]);

    // The cells' first places from the merged keys, against a count.
    std::vector<int> begin(std::size_t(grid.cells()) + 2), counted(begin.size(), 0);
    for (long c = 0; c <= grid.cells() + 1; ++c) CellBegin{merged_keys.data(), n, begin.data()}(c);
    for (int k : keys) ++counted[std::size_t(k) + 1];
    for (std::size_t c = 1; c < counted.size(); ++c) counted[c] += counted[c - 1];
    CHECK(begin == counted);
  }
}
