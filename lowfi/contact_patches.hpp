#pragma once
// Contact patches of the SCM grid: connected sets of nodes in contact (4-neighbour) and the Bekker
// width b of each, b = 2 A / P of the patch's convex hull (docs/architecture.md, "SCM and Wong-Reece";
// b = r for a circular plate). The hull of node centres is offset outward by half a cell, so that a
// patch's hull covers its cells: a single node gets b = grid / 2 instead of 0.
#include <utility>
#include <vector>

namespace terracal::lowfi {

struct GridIndex {
  int i = 0, j = 0;
};

struct ContactPatches {
  std::vector<int> patch_of;                                    // per input node: its patch
  std::vector<double> bekker_width, hull_area, hull_perimeter;  // per patch
  std::size_t count() const { return bekker_width.size(); }

  // Working memory of find_contact_patches, kept so that finding the patches every step (the SCM)
  // allocates nothing once warm.
  struct Run {
    int j, i0, i1;  // nodes (i0..i1, j), consecutive along a row
  };
  struct Work {
    std::vector<int> order, run_of, parent, id_of_root, first_run, cursor, runs_by_patch;
    std::vector<Run> runs;
    std::vector<std::pair<double, double>> points;
  } work;
};

// Patches numbered in order of their first node in `nodes` (distinct nodes); out's storage is reused.
void find_contact_patches(const std::vector<GridIndex>& nodes, double grid, ContactPatches& out);

// Convex hull area and perimeter of a point set (Andrew's monotone chain; collinear points dropped).
void convex_hull_measures(std::vector<std::pair<double, double>> points, double& area, double& perimeter);

}  // namespace terracal::lowfi
