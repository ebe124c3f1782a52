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
  std::unordered_map<std::int64_t, int> index;
  index.reserve(2 * nodes.size());
  for (std::size_t n = 0; n < nodes.size(); ++n) index.emplace(key_of(nodes[n].i, nodes[n].j), int(n));
  std::vector<int> stack;
  std::vector<std::pair<double, double>> pts;
  for (std::size_t seed = 0; seed < nodes.size(); ++seed) {
    if (out.patch_of[seed] >= 0) continue;
    const int patch = int(out.count());
    out.patch_of[seed] = patch;
    stack.assign(1, int(seed));
    pts.clear();
    while (!stack.empty()) {
      const int n = stack.back();
      stack.pop_back();
      pts.emplace_back(nodes[n].i * grid, nodes[n].j * grid);
      const int di[4] = {1, -1, 0, 0}, dj[4] = {0, 0, 1, -1};
      for (int q = 0; q < 4; ++q) {
        const auto it = index.find(key_of(nodes[n].i + di[q], nodes[n].j + dj[q]));
        if (it != index.end() && out.patch_of[it->second] < 0) {
          out.patch_of[it->second] = patch;
          stack.push_back(it->second);
        }
      }
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
