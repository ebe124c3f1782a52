#pragma once
// The collision shape of a rigid body, in its own frame: what the CRM markers are built from and
// what the SCM terrain casts its rays against. Shared by highfi, lowfi and the rigs.
#include <array>
#include <vector>

#include "core/vec.hpp"

namespace terracal {

enum class ShapeType { kBox, kCylinder, kDisc, kAnnulus, kMesh };

struct BodyShape {
  ShapeType type = ShapeType::kBox;
  Vec3<double> half_extents{};  // box
  double radius = 0;            // cylinder (axis = body y), disc and annulus outer radius (axis = body z)
  double inner_radius = 0;      // annulus
  double width = 0;             // cylinder width along y; disc/annulus thickness along z
  int grouser_count = 0;        // cylinder: straight grousers across the width
  double grouser_height = 0, grouser_thickness = 0;
  std::vector<Vec3<double>> vertices;  // triangle mesh, body frame
  std::vector<std::array<int, 3>> triangles;
};

// A wheel: a cylinder about the body y axis, optionally with straight grousers across its width.
inline BodyShape wheel_shape(double radius, double width, int grousers = 0, double grouser_height = 0,
                             double grouser_thickness = 0) {
  BodyShape s;
  s.type = ShapeType::kCylinder;
  s.radius = radius;
  s.width = width;
  s.grouser_count = grousers;
  s.grouser_height = grouser_height;
  s.grouser_thickness = grouser_thickness;
  return s;
}

}  // namespace terracal
