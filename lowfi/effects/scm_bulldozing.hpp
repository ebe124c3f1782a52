#pragma once
// SCM effect `bulldozing`: the soil a patch pushes down plastically in a step is laid on the nodes
// around the patch (its rim), then the loose surface is relaxed until no slope between neighbouring
// nodes exceeds the angle of repose. Nodes under a body are not moved. Volume is conserved: what the
// bodies push down reappears around them (ScmTerrain::volumes).
#include <algorithm>
#include <cmath>
#include <vector>

#include "lowfi/effects/scm_effect.hpp"

namespace terracal::lowfi {

struct ScmBulldozing : ScmEffect {
  static constexpr const char* kName = "bulldozing";
  struct Settings {
    double repose_angle_deg = 30;  // the slope the eroded surface relaxes to
    int erosion_sweeps = 5;        // relaxation sweeps per step
  };
  static constexpr auto settings() {
    return std::array{
        real_setting("repose_angle_deg", &Settings::repose_angle_deg, Range{1, 89, false, false, "deg"},
                     "the slope the eroded surface relaxes to"),
        whole_setting("erosion_sweeps", &Settings::erosion_sweeps, Range{0, 100}, "relaxation sweeps per step")};
  }

  static void after_contact(const Settings& s, ScmContactView& c) {
    if (c.pressed.empty()) return;
    pile_on_rims(c);
    erode(s, c);
  }

 private:
  static constexpr int kDi[4] = {1, -1, 0, 0}, kDj[4] = {0, 0, 1, -1};

  // Each patch's displaced volume, spread evenly over the free nodes around it.
  static void pile_on_rims(ScmContactView& c) {
    std::vector<std::vector<ScmNodeGrid::Key>> rims(c.patches.count());
    for (std::size_t h = 0; h < c.pressed.size(); ++h)
      for (int q = 0; q < 4; ++q) {
        const int i = c.pressed[h].i + kDi[q], j = c.pressed[h].j + kDj[q];
        if (!c.nodes.in_contact(i, j)) rims[c.patches.patch_of[h]].push_back(ScmNodeGrid::key(i, j));
      }
    for (std::size_t p = 0; p < rims.size(); ++p) {
      auto& rim = rims[p];
      std::sort(rim.begin(), rim.end());
      rim.erase(std::unique(rim.begin(), rim.end()), rim.end());
      if (rim.empty() || c.displaced[p] <= 0) continue;
      const double dh = c.displaced[p] / (double(rim.size()) * c.grid * c.grid);
      for (const auto k : rim) c.nodes.piled_to(c.nodes[k].level_offset += dh);
    }
  }

  // Sweeps over the region around the patches: a quarter of the excess over the repose slope moves
  // from the higher to the lower of each pair of free neighbours.
  static void erode(const Settings& s, ScmContactView& c) {
    int ilo = c.pressed[0].i, ihi = ilo, jlo = c.pressed[0].j, jhi = jlo;
    for (const GridIndex& n : c.pressed) {
      ilo = std::min(ilo, n.i);
      ihi = std::max(ihi, n.i);
      jlo = std::min(jlo, n.j);
      jhi = std::max(jhi, n.j);
    }
    const double max_step = c.grid * std::tan(s.repose_angle_deg * M_PI / 180.0);
    const int margin = 6;
    ScmNodeGrid& nodes = c.nodes;
    for (int sweep = 0; sweep < s.erosion_sweeps; ++sweep)
      for (int i = ilo - margin; i <= ihi + margin; ++i)
        for (int j = jlo - margin; j <= jhi + margin; ++j) {
          if (nodes.in_contact(i, j)) continue;
          for (int q = 0; q < 2; ++q) {  // +x and +y neighbours: each pair once
            const int i2 = i + kDi[2 * q], j2 = j + kDj[2 * q];
            if (nodes.in_contact(i2, j2)) continue;
            const double diff = nodes.free_surface(i, j) - nodes.free_surface(i2, j2);
            if (std::abs(diff) <= max_step) continue;
            const double move = 0.25 * (std::abs(diff) - max_step) * (diff > 0 ? 1 : -1);
            nodes[ScmNodeGrid::key(i, j)].level_offset -= move;
            nodes.piled_to(nodes[ScmNodeGrid::key(i2, j2)].level_offset += move);
            nodes.piled_to(nodes[ScmNodeGrid::key(i, j)].level_offset);
          }
        }
  }
};

}  // namespace terracal::lowfi
