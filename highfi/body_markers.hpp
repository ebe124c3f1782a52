#pragma once
// Boundary markers (DESIGN.md §4: at least 3 layers inside every wall and body surface), generated
// in the body frame at the particle spacing d0.
#include <vector>

#include "core/vec.hpp"
#include "highfi/crm_scene.hpp"

namespace terracal {

// Signed distance to the shape's surface in the body frame: negative inside.
double shape_signed_distance(const BodyShape& shape, const Vec3<double>& p);

// Marker positions in the body frame: points of a lattice of spacing ~d0 (rings for round shapes)
// that lie inside the shape within `layers` spacings of its surface.
std::vector<Vec3<double>> body_marker_positions(const BodyShape& shape, double d0, int layers);

// Wall markers of the bin (floor and four side walls up to the wall height), in world coordinates;
// the soil occupies [0, size.x] x [0, size.y] x [0, ...).
std::vector<Vec3<double>> bin_marker_positions(const CrmBin& bin, double d0);

}  // namespace terracal
