#include "core/shape_raycast.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace terracal {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;

// Each primitive narrows a parameter interval [lo, hi] (initially [0, t_max]) to where the ray is
// inside it; a convex solid is the intersection of such pieces, and its entry is the final lo.
// Closed sets throughout: touching the surface counts, as shape_signed_distance == 0 does.

// A subnormal d counts as parallel: 1 / d would overflow, and its crossings lie beyond any t_max.
inline bool is_parallel(double d) { return !(std::abs(d) >= std::numeric_limits<double>::min()); }
inline double reciprocal(double d) { return is_parallel(d) ? 0.0 : 1 / d; }

// |o + t d| <= h, with inv = reciprocal(d): the slab tests multiply, and callers that cast many
// rays along one direction compute inv once (the tests are division-bound otherwise).
inline bool clip_slab(double o, double d, double inv, double h, double& lo, double& hi) {
  if (is_parallel(d)) return std::abs(o) <= h && lo <= hi;
  double a = (-h - o) * inv, b = (h - o) * inv;
  if (a > b) std::swap(a, b);
  lo = std::max(lo, a);
  hi = std::min(hi, b);
  return lo <= hi;
}

// Roots t0 <= t1 of (ox + t dx)^2 + (oy + t dy)^2 = r^2, given a = dx^2 + dy^2 and inv_a = 1 / a
// (per direction); false when the ray never gets inside the circle. A ray parallel to the axis
// (a zero or subnormal, as for slabs) is inside for all t or none. The roots use the
// cancellation-free form (q / a, c / q) so that near-tangent and far-away rays keep full precision.
inline bool circle_roots(double ox, double oy, double dx, double dy, double a, double inv_a, double r, double& t0,
                         double& t1) {
  const double b = ox * dx + oy * dy, c = ox * ox + oy * oy - r * r;
  if (is_parallel(a)) {
    t0 = -kInf;
    t1 = kInf;
    return c <= 0;
  }
  const double disc = b * b - a * c;
  if (disc < 0) return false;
  const double q = -(b + std::copysign(std::sqrt(disc), b));
  t0 = q * inv_a;
  t1 = q != 0 ? c / q : t0;
  if (t0 > t1) std::swap(t0, t1);
  return true;
}

// Inside the infinite circular cylinder of radius r (x, y: the two coordinates across its axis).
inline bool clip_circle(double ox, double oy, double dx, double dy, double a, double inv_a, double r, double& lo,
                        double& hi) {
  double t0, t1;
  if (!circle_roots(ox, oy, dx, dy, a, inv_a, r, t0, t1)) return false;
  lo = std::max(lo, t0);
  hi = std::min(hi, t1);
  return lo <= hi;
}

}  // namespace

ShapeRaycaster::ShapeRaycaster(const BodyShape& s) : type_(s.type) {
  switch (s.type) {
    case ShapeType::kBox:
      half_ = s.half_extents;
      lo_ = -half_;
      hi_ = half_;
      break;
    case ShapeType::kCylinder: {
      radius_ = s.radius;
      half_width_ = 0.5 * s.width;
      lo_ = {-radius_, -half_width_, -radius_};
      hi_ = {radius_, half_width_, radius_};
      // A grouser without thickness or height has no volume (the signed distance never goes below
      // 0 there), so the ray has nothing to enter: skipped rather than hit on a zero-width plate.
      if (s.grouser_count > 0 && s.grouser_height > 0 && s.grouser_thickness > 0) {
        g_mid_ = s.radius + 0.5 * s.grouser_height - 0.5 * s.grouser_thickness;
        g_half_radial_ = 0.5 * (s.grouser_height + s.grouser_thickness);
        g_half_tangential_ = 0.5 * s.grouser_thickness;
        // Cylinder through the grousers' outer corners (plus rounding slack): rays that miss it
        // before the best hit so far skip all grouser tests.
        g_outer_radius_ = std::hypot(g_mid_ + g_half_radial_, g_half_tangential_) * (1 + 1e-12);
        // Culling needs every grouser point outside the rim circle to have a positive radial
        // coordinate (R > thickness); the margin covers rounding of the angles.
        g_cull_ = s.radius > s.grouser_thickness;
        if (g_cull_) g_half_angle_ = std::asin(g_half_tangential_ / s.radius) + 1e-9;
        g_per_radian_ = s.grouser_count / (2 * kPi);
        grousers_.reserve(std::size_t(s.grouser_count));
        for (int g = 0; g < s.grouser_count; ++g) {
          // Same angle expression as shape_signed_distance, so both see bit-identical grousers.
          const double a = 2 * kPi * g / s.grouser_count;
          const Grouser gr{std::cos(a), std::sin(a)};
          grousers_.push_back(gr);
          for (double r : {g_mid_ - g_half_radial_, g_mid_ + g_half_radial_})
            for (double t : {-g_half_tangential_, g_half_tangential_}) {
              const double x = gr.c * r - gr.s * t, z = gr.s * r + gr.c * t;
              lo_.x = std::min(lo_.x, x);
              hi_.x = std::max(hi_.x, x);
              lo_.z = std::min(lo_.z, z);
              hi_.z = std::max(hi_.z, z);
            }
        }
      }
      break;
    }
    case ShapeType::kDisc:
    case ShapeType::kAnnulus:
      radius_ = s.radius;
      inner_ = s.type == ShapeType::kAnnulus ? s.inner_radius : 0.0;
      half_width_ = 0.5 * s.width;
      lo_ = {-radius_, -radius_, -half_width_};
      hi_ = {radius_, radius_, half_width_};
      break;
    case ShapeType::kMesh:
      bvh_ = TriangleBvh(s.vertices, s.triangles);
      if (!s.vertices.empty()) {
        lo_ = hi_ = s.vertices[0];
        for (const auto& v : s.vertices)
          for (int k = 0; k < 3; ++k) {
            lo_[k] = std::min(lo_[k], v[k]);
            hi_[k] = std::max(hi_[k], v[k]);
          }
      }
      break;
  }
}

ShapeRaycaster::Direction ShapeRaycaster::direction(const Vec3<double>& d) const {
  Direction r;
  r.d = d;
  r.inv = {reciprocal(d.x), reciprocal(d.y), reciprocal(d.z)};
  const double across = type_ == ShapeType::kCylinder ? d.z : d.y;  // the second coordinate across the round axis
  r.a = d.x * d.x + across * across;
  r.inv_a = reciprocal(r.a);
  return r;
}

double ShapeRaycaster::first_hit(const Vec3<double>& o, const Vec3<double>& d, double t_max) const {
  return first_hit(direction(d), o, t_max);
}

double ShapeRaycaster::first_hit(const Direction& d, const Vec3<double>& o, double t_max) const {
  if (!(t_max >= 0)) return kInf;
  switch (type_) {
    case ShapeType::kBox: {
      double lo = 0, hi = t_max;
      const bool hit = clip_slab(o.x, d.d.x, d.inv.x, half_.x, lo, hi) &&
                       clip_slab(o.y, d.d.y, d.inv.y, half_.y, lo, hi) &&
                       clip_slab(o.z, d.d.z, d.inv.z, half_.z, lo, hi);
      return hit ? lo : kInf;
    }
    case ShapeType::kCylinder:
      return cylinder_hit(o, d, t_max);
    case ShapeType::kDisc:
    case ShapeType::kAnnulus:
      return round_plate_hit(o, d, t_max);
    case ShapeType::kMesh:
      // Inside is not detected for meshes: the first triangle crossed is returned (the exit point
      // for an origin inside). The SCM casts from the terrain below the body, outside it, and an
      // inside test would need a second full traversal (crossing parity) on every call.
      return bvh_.first_hit(o, d.d, t_max);
  }
  return kInf;
}

void ShapeRaycaster::first_hits(const Direction& d, const Vec3<double>& origin, const Vec3<double>& step, int k0,
                                int k1, double t_max, double* t) const {
  auto row = [&](auto hit) {
    for (int k = k0; k < k1; ++k) t[k] = hit(origin + double(k) * step);
  };
  // Cylinders (the SCM's wheels) skip first_hit's switch, so that the rim test inlines into the
  // loop and the processor overlaps the square roots and divisions of neighbouring rays, which
  // bound it otherwise (each ray's entry waits on both).
  if (type_ == ShapeType::kCylinder && t_max >= 0)
    row([&](const Vec3<double>& o) { return cylinder_hit(o, d, t_max); });
  else
    row([&](const Vec3<double>& o) { return first_hit(d, o, t_max); });
}

// The solid is the union of the rim (convex) and the grousers (convex each): its first point is
// the smallest entry over the pieces. All pieces share the slab |y| <= width / 2.
inline double ShapeRaycaster::cylinder_hit(const Vec3<double>& o, const Direction& dir, double t_max) const {
  const Vec3<double>& d = dir.d;
  double lo = 0, hi = t_max;
  if (!clip_slab(o.y, d.y, dir.inv.y, half_width_, lo, hi)) return kInf;
  double best = kInf;
  double rl = lo, rh = hi;
  if (clip_circle(o.x, o.z, d.x, d.z, dir.a, dir.inv_a, radius_, rl, rh)) best = rl;
  if (grousers_.empty() || best == lo) return best;  // nothing can be entered before lo
  return grouser_hit(o, dir, lo, std::min(hi, best), best);
}

// The first grouser entry in [lo, hi] if before best, else best. [lo, hi]: where the ray is within
// the wheel's slab, cut at the rim's entry.
double ShapeRaycaster::grouser_hit(const Vec3<double>& o, const Direction& dir, double lo, double hi,
                                   double best) const {
  const Vec3<double>& d = dir.d;
  double gl = lo, gh = hi;
  if (!clip_circle(o.x, o.z, d.x, d.z, dir.a, dir.inv_a, g_outer_radius_, gl, gh)) return best;
  // Angular culling. On [gl, te] the ray is outside the rim circle (else the rim is entered first),
  // so it sweeps an angle below pi, and a grouser point at radius r >= R lies within
  // g_half_angle_ of the grouser's axis: only grousers whose axis angle is within that much of the
  // sweep can be hit first.
  const int n = int(grousers_.size());
  int k0 = 0, k1 = n - 1;
  const double te = std::min(gh, best);
  if (g_cull_ && std::isfinite(te)) {
    const double ax = o.x + gl * d.x, az = o.z + gl * d.z, bx = o.x + te * d.x, bz = o.z + te * d.z;
    const double ta = std::atan2(az, ax), sweep = std::atan2(ax * bz - az * bx, ax * bx + az * bz);
    const double lo_a = std::min(ta, ta + sweep) - g_half_angle_, hi_a = std::max(ta, ta + sweep) + g_half_angle_;
    k0 = int(std::ceil(lo_a * g_per_radian_));
    k1 = std::min(int(std::floor(hi_a * g_per_radian_)), k0 + n - 1);
  }
  for (int k = k0; k <= k1; ++k) {
    const Grouser& g = grousers_[std::size_t((k % n + n) % n)];
    // The ray in the grouser's frame (radial, y, tangential), centred on the grouser.
    const double orad = g.c * o.x + g.s * o.z - g_mid_, drad = g.c * d.x + g.s * d.z;
    const double otan = -g.s * o.x + g.c * o.z, dtan = -g.s * d.x + g.c * d.z;
    double l = gl, h = std::min(gh, best);
    if (clip_slab(orad, drad, reciprocal(drad), g_half_radial_, l, h) &&
        clip_slab(otan, dtan, reciprocal(dtan), g_half_tangential_, l, h))
      best = l;
  }
  return best;
}

// Disc: slab in z times the circle r <= R. Annulus: the same minus the open hole r < r_inner, which
// cuts the convex interval [lo, hi] at most once from the front: the entry is lo unless lo lies in
// the hole, then the far side of the hole (if still within hi).
double ShapeRaycaster::round_plate_hit(const Vec3<double>& o, const Direction& dir, double t_max) const {
  const Vec3<double>& d = dir.d;
  double lo = 0, hi = t_max;
  if (!clip_slab(o.z, d.z, dir.inv.z, half_width_, lo, hi) ||
      !clip_circle(o.x, o.y, d.x, d.y, dir.a, dir.inv_a, radius_, lo, hi))
    return kInf;
  if (inner_ > 0) {
    double h0, h1;
    if (circle_roots(o.x, o.y, d.x, d.y, dir.a, dir.inv_a, inner_, h0, h1)) {
      // Parallel to the axis: circle_roots reports "inside for all t" for r <= r_inner; only a
      // strictly inside ray (r < r_inner) is in the open hole.
      const bool parallel = h0 == -kInf;
      const bool in_hole = parallel ? (o.x * o.x + o.y * o.y < inner_ * inner_) : (lo > h0 && lo < h1);
      if (in_hole) {
        if (parallel || h1 > hi) return kInf;
        lo = h1;
      }
    }
  }
  return lo;
}

}  // namespace terracal
