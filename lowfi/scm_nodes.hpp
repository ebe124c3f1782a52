#pragma once
// The SCM's sparse grid of nodes (docs/architecture.md, "SCM and Wong-Reece"): keyed by integer node
// coordinates, only nodes a body has touched are stored, so the patch is unbounded and a neighbour is
// one lookup.
#include <algorithm>
#include <cstdint>
#include <unordered_map>

#include "core/vec.hpp"

namespace terracal::lowfi {

// One stored node: what a node remembers between steps.
struct ScmNode {
  double plastic_sinkage = 0;  // z_p below the undisturbed surface
  double last_sinkage = 0;     // the sinkage at the last step of the current contact
  double sigma = 0;            // normal pressure at the last step [Pa]
  double tau = 0;              // shear stress at the last step [Pa]
  Vec3<double> shear{};        // accumulated shear displacement of the current contact [m]
  double level_offset = 0;     // soil added (+) or removed (-) on top of the undisturbed surface (bulldozing)
  bool in_contact = false;
  long contact_step = -1;  // the last step this node was in contact (releases the others)
};

class ScmNodeGrid {
 public:
  using Key = std::int64_t;
  using Map = std::unordered_map<Key, ScmNode>;

  explicit ScmNodeGrid(double surface_height = 0) : surface_height_(surface_height) {}

  static Key key(int i, int j) { return (Key(i) << 32) ^ Key(std::uint32_t(j)); }
  // Node (i, j), or nullptr if never touched.
  const ScmNode* find(int i, int j) const {
    const auto it = nodes_.find(key(i, j));
    return it == nodes_.end() ? nullptr : &it->second;
  }
  Map::iterator find(Key k) { return nodes_.find(k); }
  Map::iterator end() { return nodes_.end(); }
  Map::iterator emplace(Key k) { return nodes_.emplace(k, ScmNode{}).first; }
  // Node k, stored now if it was not (std::unordered_map::operator[]).
  ScmNode& operator[](Key k) { return nodes_[k]; }
  const Map& nodes() const { return nodes_; }
  std::size_t size() const { return nodes_.size(); }

  bool in_contact(int i, int j) const {
    const ScmNode* n = find(i, j);
    return n && n->in_contact;
  }
  // The soil surface at node (i, j) when no body presses on it.
  double free_surface(int i, int j) const {
    const ScmNode* n = find(i, j);
    return surface_height_ + (n ? n->level_offset - n->plastic_sinkage : 0.0);
  }
  double surface_height() const { return surface_height_; }
  // The highest the soil was piled above the undisturbed surface (bounds the rays from above).
  double max_level_offset() const { return max_level_offset_; }
  // Records that some node's level offset is now `level`.
  void piled_to(double level) { max_level_offset_ = std::max(max_level_offset_, level); }

 private:
  Map nodes_;
  double surface_height_ = 0;
  double max_level_offset_ = 0;
};

}  // namespace terracal::lowfi
