#include "lowfi/contact_patches.hpp"

#include <algorithm>
#include <cmath>

namespace terracal::lowfi {

namespace {
double cross(const std::pair<double, double>& o, const std::pair<double, double>& a,
             const std::pair<double, double>& b) {
  return (a.first - o.first) * (b.second - o.second) - (a.second - o.second) * (b.first - o.first);
}

// Union-find over runs, the root of a set being its smallest run (path halving).
int root(std::vector<int>& parent, int r) {
  while (parent[r] != r) r = parent[r] = parent[parent[r]];
  return r;
}
void join(std::vector<int>& parent, int a, int b) {
  a = root(parent, a);
  b = root(parent, b);
  parent[std::max(a, b)] = std::min(a, b);
}

// The nodes in row order (j, then i), split into runs of consecutive i; run_of: each node's run.
// The SCM lists its nodes in row order already (one body's rays, row by row), so the sort is for
// other callers and several bodies.
void make_runs(const std::vector<GridIndex>& nodes, ContactPatches::Work& w) {
  auto before = [&](int a, int b) {
    return nodes[a].j != nodes[b].j ? nodes[a].j < nodes[b].j : nodes[a].i < nodes[b].i;
  };
  w.order.resize(nodes.size());
  for (std::size_t n = 0; n < nodes.size(); ++n) w.order[n] = int(n);
  if (!std::is_sorted(w.order.begin(), w.order.end(), before)) std::sort(w.order.begin(), w.order.end(), before);
  w.runs.clear();
  w.run_of.resize(nodes.size());
  for (const int n : w.order) {
    const GridIndex& g = nodes[n];
    if (w.runs.empty() || w.runs.back().j != g.j || g.i > w.runs.back().i1 + 1) w.runs.push_back({g.j, g.i, g.i});
    w.runs.back().i1 = g.i;
    w.run_of[n] = int(w.runs.size()) - 1;
  }
}

// Joins the runs of neighbouring rows that overlap in i (4-neighbour contact). Runs are in row
// order, so each pair of rows is walked together once.
void join_rows(ContactPatches::Work& w) {
  const auto& runs = w.runs;
  const int n = int(runs.size());
  w.parent.resize(runs.size());
  for (int r = 0; r < n; ++r) w.parent[r] = r;
  for (int prev = 0, cur = 0; cur < n;) {  // the first run of the previous row and of this row
    int end = cur;
    while (end < n && runs[end].j == runs[cur].j) ++end;
    if (cur > 0 && runs[prev].j == runs[cur].j - 1)
      for (int c = cur, p = prev; c < end; ++c) {
        while (p < cur && runs[p].i1 < runs[c].i0) ++p;  // ends before run c, so before the runs after it
        for (int q = p; q < cur && runs[q].i0 <= runs[c].i1; ++q) join(w.parent, c, q);
      }
    prev = cur;
    cur = end;
  }
}

// Patch numbers in order of each patch's first node, and each patch's runs (in row order):
// runs_by_patch[first_run[p] .. first_run[p + 1]).
void number_patches(ContactPatches& out) {
  auto& w = out.work;
  w.id_of_root.assign(w.runs.size(), -1);
  int patches = 0;
  for (std::size_t n = 0; n < out.patch_of.size(); ++n) {
    int& id = w.id_of_root[root(w.parent, w.run_of[n])];
    if (id < 0) id = patches++;
    out.patch_of[n] = id;
  }
  // A counting sort of the runs by patch.
  w.first_run.assign(std::size_t(patches) + 1, 0);
  for (int r = 0; r < int(w.runs.size()); ++r) ++w.first_run[w.id_of_root[root(w.parent, r)] + 1];
  for (int p = 0; p < patches; ++p) w.first_run[p + 1] += w.first_run[p];
  w.runs_by_patch.resize(w.runs.size());
  w.cursor.assign(w.first_run.begin(), w.first_run.end() - 1);
  for (int r = 0; r < int(w.runs.size()); ++r) w.runs_by_patch[w.cursor[w.id_of_root[root(w.parent, r)]]++] = r;
}

// The convex hull of patch p: the hull of each row's two ends (its runs are in row order, and
// along a row in order of i).
void patch_hull(ContactPatches::Work& w, int p, double grid, double& area, double& perimeter) {
  w.points.clear();
  const int end = w.first_run[p + 1];
  for (int k = w.first_run[p]; k < end;) {
    const ContactPatches::Run& first = w.runs[w.runs_by_patch[k]];
    while (k + 1 < end && w.runs[w.runs_by_patch[k + 1]].j == first.j) ++k;
    const int i1 = w.runs[w.runs_by_patch[k++]].i1;
    w.points.emplace_back(first.i0 * grid, first.j * grid);
    if (i1 != first.i0) w.points.emplace_back(i1 * grid, first.j * grid);
  }
  convex_hull_measures(w.points, area, perimeter);
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

void find_contact_patches(const std::vector<GridIndex>& nodes, double grid, ContactPatches& out) {
  out.patch_of.resize(nodes.size());
  out.bekker_width.clear();
  out.hull_area.clear();
  out.hull_perimeter.clear();
  make_runs(nodes, out.work);
  join_rows(out.work);
  number_patches(out);
  for (std::size_t p = 0; p + 1 < out.work.first_run.size(); ++p) {
    double a = 0, perim = 0;
    patch_hull(out.work, int(p), grid, a, perim);
    // Offset the hull by half a cell: A' = A + P d + pi d^2, P' = P + 2 pi d (Steiner's formula).
    const double d = 0.5 * grid;
    const double area = a + perim * d + M_PI * d * d, perimeter = perim + 2 * M_PI * d;
    out.hull_area.push_back(area);
    out.hull_perimeter.push_back(perimeter);
    out.bekker_width.push_back(2 * area / perimeter);
  }
}

}  // namespace terracal::lowfi
