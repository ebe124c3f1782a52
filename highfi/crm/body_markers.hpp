#pragma once
// Boundary markers (at least 3 layers inside every wall and body surface; docs/architecture.md,
// "CRM"), generated in the body frame at the particle spacing d0.
#include <vector>

#include "core/vec.hpp"
#include "highfi/crm/crm_scene.hpp"

namespace terracal {

// Signed distance to the shape's surface in the body frame: negative inside.
double shape_signed_distance(const BodyShape& shape, const Vec3<double>& p);

// Marker positions in the body frame: points of a lattice of spacing ~d0 (rings for round shapes)
// that lie inside the shape within `layers` spacings of its surface.
std::vector<Vec3<double>> body_marker_positions(const BodyShape& shape, double d0, int layers);

// Wall markers of the bin (floor and four side walls up to the wall height), in world coordinates;
// the soil occupies [0, size.x] x [0, size.y] x [0, ...).
std::vector<Vec3<double>> bin_marker_positions(const CrmBin& bin, double d0);

// The way from a marker to the soil, for MarkerVelocity::kMirrorImage: unit normal (x, y, z) of the
// nearest surface point, pointing out of the wall, and w = the marker's depth below that surface.
// A body marker's normal is the gradient of the shape's distance field, in the body frame; a bin
// marker's points to the nearest point of the soil's room [0, size.x] x [0, size.y] x [0, inf).
// w = 0 for a point that is not inside the wall; a zero normal with w > 0 for one equally deep below
// two faces (the distance field has no gradient there).
Vec4<double> body_marker_normal(const BodyShape& shape, const Vec3<double>& local, double d0);
Vec4<double> bin_marker_normal(const CrmBin& bin, const Vec3<double>& p);

}  // namespace terracal
