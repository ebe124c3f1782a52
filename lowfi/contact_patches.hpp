#pragma once
// Contact patches of the SCM grid: connected sets of nodes in contact (4-neighbour flood fill) and
// the Bekker width b of each, b = 2 A / P of the patch's convex hull (DESIGN.md section 4; b = r
// for a circular plate). The hull of node centres is offset outward by half a cell, so that a
// patch's hull covers its cells: a single node gets b = grid / 2 instead of 0.
#include <cstdint>
#include <vector>

namespace terracal::lowfi {

struct GridIndex {
  int i = 0, j = 0;
};

struct ContactPatches {
  std::vector<int> patch_of;  // per input node: its patch
  std::vector<double> bekker_width, hull_area, hull_perimeter;  // per patch
  std::size_t count() const { return bekker_width.size(); }
};

ContactPatches find_contact_patches(const std::vector<GridIndex>& nodes, double grid);

// Convex hull area and perimeter of a point set (Andrew's monotone chain; collinear points dropped).
void convex_hull_measures(std::vector<std::pair<double, double>> points, double& area, double& perimeter);

}  // namespace terracal::lowfi
