#include "lowfi/contact_patches.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace terracal::lowfi {

namespace {
std::int64_t key_of(int i, int j) { return (std::int64_t(i) << 32) ^ std::int64_t(std::uint32_t(j)); }
double cross(const std::pair<double, double>& o, const std::pair<double, double>& a, const std::pair<double, double>& b) {
  return (a.first - o.first) * (b.second - o.second) - (a.second - o.second) * (b.first - o.first);
}
}  // namespace

void convex_hull_measures(std::vector<std::pair<double, double>> p, double& area, double& perimeter) {
  area = perimeter = 0;
  std::sort(p.begin(), p.end());
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 2) return;
  std::vector<std::pair<double, double>> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {  // lower hull
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {  // upper hull
    while (k >= t && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);  // the last point repeats the first
  for (std::size_t a = 0; a < h.size(); ++a) {
    const auto& u = h[a];
    const auto& v = h[(a + 1) % h.size()];
    area += u.first * v.second - v.first * u.second;
    perimeter += std::hypot(v.first - u.first, v.second - u.second);
  }
  area = 0.5 * std::abs(area);
}

ContactPatches find_contact_patches(const std::vector<GridIndex>& nodes, double grid) {
  ContactPatches out;
  out.patch_of.assign(nodes.size(), -1);
  if (nodes.empty()) return out;
  // The nodes' bounding box as a dense index (contacts are compact, so this is small and beats a
  // hash map by an order of magnitude).
  int ilo = nodes[0].i, ihi = ilo, jlo = nodes[0].j, jhi = jlo;
  for (const auto& n : nodes) {
    ilo = std::min(ilo, n.i), ihi = std::max(ihi, n.i);
    jlo = std::min(jlo, n.j), jhi = std::max(jhi, n.j);
  }
  const long w = long(ihi) - ilo + 1, h = long(jhi) - jlo + 1;
  std::vector<int> index;
  std::unordered_map<std::int64_t, int> sparse;  // for scattered contacts (several distant bodies)
  const bool dense = w * h <= 64 * long(nodes.size()) + 4096;
  if (dense) {
    index.assign(std::size_t(w * h), -1);
    for (std::size_t n = 0; n < nodes.size(); ++n) index[std::size_t((nodes[n].j - jlo) * w + (nodes[n].i - ilo))] = int(n);
  } else {
    sparse.reserve(2 * nodes.size());
    for (std::size_t n = 0; n < nodes.size(); ++n) sparse.emplace(key_of(nodes[n].i, nodes[n].j), int(n));
  }
  auto find = [&](int i, int j) -> int {
    if (i < ilo || i > ihi || j < jlo || j > jhi) return -1;
    if (dense) return index[std::size_t((j - jlo) * w + (i - ilo))];
    const auto it = sparse.find(key_of(i, j));
    return it == sparse.end() ? -1 : it->second;
  };
  std::vector<int> stack;
  std::vector<std::pair<double, double>> pts;
  // Per row j of the patch being filled: its min and max i (rows indexed from jlo; rows[] holds
  // the rows touched, so that resetting costs only what the patch used).
  // Bodies far apart in j (sparse) keep the extents in a map instead of a vector over the gap.
  const bool dense_rows = h <= 4 * long(nodes.size()) + 4096;
  std::vector<std::pair<int, int>> extent(dense_rows ? std::size_t(h) : 0, {1, 0});  // empty: min > max
  std::unordered_map<int, std::pair<int, int>> extent_far;
  auto row = [&](int j) -> std::pair<int, int>& {
    return dense_rows ? extent[std::size_t(j - jlo)] : extent_far.try_emplace(j, 1, 0).first->second;
  };
  std::vector<int> rows;
  for (std::size_t seed = 0; seed < nodes.size(); ++seed) {
    if (out.patch_of[seed] >= 0) continue;
    const int patch = int(out.count());
    out.patch_of[seed] = patch;
    stack.assign(1, int(seed));
    rows.clear();
    while (!stack.empty()) {
      const int n = stack.back();
      stack.pop_back();
      auto& e = row(nodes[n].j);
      if (e.first > e.second) {
        e = {nodes[n].i, nodes[n].i};
        rows.push_back(nodes[n].j);
      } else {
        e = {std::min(e.first, nodes[n].i), std::max(e.second, nodes[n].i)};
      }
      const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
      for (int q = 0; q < 4; ++q) {
        const int m = find(nodes[n].i + di[q], nodes[n].j + dj[q]);
        if (m >= 0 && out.patch_of[m] < 0) {
          out.patch_of[m] = patch;
          stack.push_back(m);
        }
      }
    }
    // The hull of a set of grid points is the hull of each row's two ends.
    pts.clear();
    for (const int j : rows) {
      auto& e = row(j);
      pts.emplace_back(e.first * grid, j * grid);
      if (e.second != e.first) pts.emplace_back(e.second * grid, j * grid);
      e = {1, 0};
    }
    double a = 0, p = 0;
    convex_hull_measures(pts, a, p);
    // Offset the hull by half a cell: A' = A + P d + pi d^2, P' = P + 2 pi d (Steiner's formula).
    const double d = 0.5 * grid;
    const double area = a + p * d + M_PI * d * d, perimeter = p + 2 * M_PI * d;
    out.hull_area.push_back(area);
    out.hull_perimeter.push_back(perimeter);
    out.bekker_width.push_back(2 * area / perimeter);
  }
  return out;
}

}  // namespace terracal::lowfi
