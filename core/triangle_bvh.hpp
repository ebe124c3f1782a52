#pragma once
// A bounding-volume hierarchy over a triangle mesh, for the SCM terrain's ray casts against mesh
// bodies. Built once from the mesh (body frame) and read-only afterwards, so one instance can be
// queried from many threads at once.
#include <array>
#include <vector>

#include "core/vec.hpp"

namespace terracal {

class TriangleBvh {
 public:
  TriangleBvh() = default;
  TriangleBvh(const std::vector<Vec3<double>>& vertices, const std::vector<std::array<int, 3>>& triangles);

  // Smallest t in [0, t_max] with origin + t dir on a triangle (either side); +infinity if none.
  // dir need not be unit. Allocates nothing: the traversal stack lives on the call stack.
  double first_hit(const Vec3<double>& origin, const Vec3<double>& dir, double t_max) const;

  bool empty() const { return nodes_.empty(); }

 private:
  // Interior nodes have count == 0: their left child is the next node (depth-first layout, so the
  // near child is usually already in cache) and `index` is the right child. Leaves hold triangles
  // [index, index + count) of tris_.
  struct Node {
    Vec3<double> box[2];  // lower and upper corner
    int index = 0, count = 0;
  };
  // Möller–Trumbore needs only one vertex and two edges: precomputed so a leaf test does no
  // vertex gathering through the index array.
  struct Tri {
    Vec3<double> v0, e1, e2;
  };
  int build(std::vector<int>& order, std::vector<Vec3<double>>& centroids,
            std::vector<std::array<Vec3<double>, 2>>& boxes, int begin, int end, int depth);

  std::vector<Node> nodes_;
  std::vector<Tri> tris_;
};

}  // namespace terracal
