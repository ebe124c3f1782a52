#pragma once
// Ray casts against a rigid body's collision shape (core/body_shape.hpp), in the body frame: the SCM
// terrain uses them to find how far above each grid node the body's underside is. The solids are
// exactly those of shape_signed_distance (highfi/crm/body_markers.cpp), where it is <= 0.
#include <algorithm>
#include <vector>

#include "core/body_shape.hpp"
#include "core/triangle_bvh.hpp"
#include "core/vec.hpp"

namespace terracal {

class ShapeRaycaster {
 public:
  // Copies what the queries need (dimensions, each grouser's sin/cos) and builds the BVH of a mesh,
  // so that first_hit allocates nothing and evaluates no trigonometry.
  explicit ShapeRaycaster(const BodyShape& shape);

  // Body frame. Smallest t in [0, t_max] where origin + t dir enters (or is inside) the solid;
  // +infinity if it misses. If the origin is already inside the solid, returns 0. dir need not be
  // unit. Meshes: the first triangle hit, "inside" is not detected (see first_hit's comment).
  double first_hit(const Vec3<double>& origin, const Vec3<double>& dir, double t_max) const;

  // What all rays of one direction share, so that many parallel rays (the SCM casts every ray under
  // a body along one body-frame direction) divide by the direction once instead of once per ray:
  // the reciprocals of its components (slab tests) and the leading coefficient of the round
  // shapes' circle equation with its reciprocal. Belongs to the caster that made it.
  struct Direction {
    Direction() = default;    // not an aggregate, so that first_hit({x, y, z}, dir, t) stays unambiguous
    Vec3<double> d{}, inv{};  // the direction; 1 / its components (0 where the ray counts as parallel)
    double a = 0, inv_a = 0;  // |d|^2 across the round axis (cylinder: x, z; disc and annulus: x, y); 1 / a
  };
  Direction direction(const Vec3<double>& dir) const;
  // first_hit(origin, dir.d, t_max), with dir from direction().
  double first_hit(const Direction& dir, const Vec3<double>& origin, double t_max) const;
  // A row of parallel rays: t[k] = first_hit(dir, origin + k step, t_max) for k in [k0, k1). The
  // origin of ray k depends on k only, not on [k0, k1), so a ray gives the same answer in any row.
  void first_hits(const Direction& dir, const Vec3<double>& origin, const Vec3<double>& step, int k0, int k1,
                  double t_max, double* t) const;

  // How far thin features (grousers) reach beyond the smooth body: a coarse ray that hits the rim
  // may miss a grouser this much lower.
  double feature_depth() const { return grousers_.empty() ? 0.0 : g_outer_radius_ - radius_; }
  // Whether the underside is known to be smooth up to feature_depth(): not for arbitrary meshes.
  bool smooth_underside() const { return type_ != ShapeType::kMesh; }
  // How far the underside can dip below the higher of two points `span` apart on a line through its
  // lowest part (cylinders: their curvature, span^2 / r; flat-bottomed shapes tilted up to 45 degrees:
  // span), and the narrowest solid part seen from below (an annulus's ring), which a coarse pass
  // must not step over.
  double dip_over(double span) const { return type_ == ShapeType::kCylinder ? span * span / radius_ : span; }
  double narrowest() const {
    switch (type_) {
      case ShapeType::kAnnulus:
        return radius_ - inner_;
      case ShapeType::kDisc:
        return 2 * radius_;
      case ShapeType::kCylinder:
        return std::min(2 * radius_, 2 * half_width_);
      case ShapeType::kBox:
        return 2 * std::min(half_.x, half_.y);
      default:
        return 0;
    }
  }

  // Axis-aligned bounds of the solid in the body frame (grousers included).
  Vec3<double> bounds_lo() const { return lo_; }
  Vec3<double> bounds_hi() const { return hi_; }

 private:
  struct Grouser {
    double c, s;  // cos and sin of its angle: radial = c x + s z, tangential = -s x + c z
  };
  double cylinder_hit(const Vec3<double>& o, const Direction& d, double t_max) const;
  double grouser_hit(const Vec3<double>& o, const Direction& d, double lo, double hi, double best) const;
  double round_plate_hit(const Vec3<double>& o, const Direction& d, double t_max) const;

  ShapeType type_;
  Vec3<double> half_{};  // box half extents
  double radius_ = 0, inner_ = 0, half_width_ = 0;
  // Grousers: boxes with centre `mid` along their radial axis and half sizes (gr, half_width_, gt).
  std::vector<Grouser> grousers_;
  double g_mid_ = 0, g_half_radial_ = 0, g_half_tangential_ = 0, g_outer_radius_ = 0;
  // Angular culling of grousers (see cylinder_hit): half-angle of a grouser seen from radius R,
  // grousers per radian, and whether the geometry allows culling at all.
  double g_half_angle_ = 0, g_per_radian_ = 0;
  bool g_cull_ = false;
  TriangleBvh bvh_;
  Vec3<double> lo_{}, hi_{};
};

}  // namespace terracal
