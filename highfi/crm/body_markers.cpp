#include "highfi/crm/body_markers.hpp"

#include <algorithm>
#include <cmath>

namespace terracal {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Distance field of an axis-aligned box of half extents e centred at the origin.
double box_sdf(const Vec3<double>& p, const Vec3<double>& e) {
  const Vec3<double> q{std::abs(p.x) - e.x, std::abs(p.y) - e.y, std::abs(p.z) - e.z};
  const Vec3<double> out{std::max(q.x, 0.0), std::max(q.y, 0.0), std::max(q.z, 0.0)};
  return norm(out) + std::min(std::max({q.x, q.y, q.z}), 0.0);
}
// Two-dimensional version for extrusions: radial excess a and axial excess b.
double extrusion_sdf(double a, double b) {
  return std::hypot(std::max(a, 0.0), std::max(b, 0.0)) + std::min(std::max(a, b), 0.0);
}

double point_triangle_distance2(const Vec3<double>& p, const Vec3<double>& a, const Vec3<double>& b,
                                const Vec3<double>& c) {
  // Ericson, Real-Time Collision Detection, closest point on a triangle.
  const Vec3<double> ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  auto d2of = [&](const Vec3<double>& q) { return dot(p - q, p - q); };
  if (d1 <= 0 && d2 <= 0) return d2of(a);
  const Vec3<double> bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return d2of(b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return d2of(a + (d1 / (d1 - d3)) * ab);
  const Vec3<double> cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return d2of(c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return d2of(a + (d2 / (d2 - d6)) * ac);
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return d2of(b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b));
  const double denom = 1.0 / (va + vb + vc);
  return d2of(a + (vb * denom) * ab + (vc * denom) * ac);
}

double mesh_sdf(const BodyShape& s, const Vec3<double>& p) {
  double d2 = 1e300;
  int crossings = 0;
  for (const auto& t : s.triangles) {
    const Vec3<double>&a = s.vertices[t[0]], &b = s.vertices[t[1]], &c = s.vertices[t[2]];
    d2 = std::min(d2, point_triangle_distance2(p, a, b, c));
    // Parity of crossings of the ray p + s (1, 1e-3, 2e-3), slightly skewed to avoid edges.
    const Vec3<double> dir{1, 1.234e-3, 2.345e-3};
    const Vec3<double> e1 = b - a, e2 = c - a, pv = cross(dir, e2);
    const double det = dot(e1, pv);
    if (std::abs(det) < 1e-300) continue;
    const Vec3<double> tv = p - a;
    const double u = dot(tv, pv) / det;
    if (u < 0 || u > 1) continue;
    const Vec3<double> qv = cross(tv, e1);
    const double v = dot(dir, qv) / det;
    if (v < 0 || u + v > 1) continue;
    if (dot(e2, qv) / det > 0) ++crossings;
  }
  const double d = std::sqrt(d2);
  return (crossings % 2) ? -d : d;
}

// Centred lattice coordinates covering [-ext, ext] at spacing ~d0.
std::vector<double> centred(double ext, double d0) {
  const int n = std::max(1, int(std::lround(2 * ext / d0)));
  const double step = 2 * ext / n;
  std::vector<double> v(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) v[std::size_t(i)] = -ext + (i + 0.5) * step;
  return v;
}

}  // namespace

double shape_signed_distance(const BodyShape& s, const Vec3<double>& p) {
  switch (s.type) {
    case ShapeType::kBox:
      return box_sdf(p, s.half_extents);
    case ShapeType::kCylinder: {
      double d = extrusion_sdf(std::hypot(p.x, p.z) - s.radius, std::abs(p.y) - 0.5 * s.width);
      for (int g = 0; g < s.grouser_count; ++g) {
        // Grouser g: a plate along the wheel's width at angle 2 pi g / count, from inside the rim to R + height.
        const double a = 2 * kPi * g / s.grouser_count;
        const double ca = std::cos(a), sa = std::sin(a);
        const double radial = ca * p.x + sa * p.z, tangential = -sa * p.x + ca * p.z;
        const double mid = s.radius + 0.5 * s.grouser_height - 0.5 * s.grouser_thickness;
        const Vec3<double> q{radial - mid, p.y, tangential};
        d = std::min(
            d, box_sdf(q, {0.5 * (s.grouser_height + s.grouser_thickness), 0.5 * s.width, 0.5 * s.grouser_thickness}));
      }
      return d;
    }
    case ShapeType::kDisc:
      return extrusion_sdf(std::hypot(p.x, p.y) - s.radius, std::abs(p.z) - 0.5 * s.width);
    case ShapeType::kAnnulus: {
      const double r = std::hypot(p.x, p.y);
      return extrusion_sdf(std::max(r - s.radius, s.inner_radius - r), std::abs(p.z) - 0.5 * s.width);
    }
    case ShapeType::kMesh:
      return mesh_sdf(s, p);
  }
  return 1e300;
}

std::vector<Vec3<double>> body_marker_positions(const BodyShape& s, double d0, int layers) {
  std::vector<Vec3<double>> out;
  const double depth = layers * d0;
  auto keep = [&](const Vec3<double>& p) {
    const double d = shape_signed_distance(s, p);
    if (d <= 1e-12 && d > -depth) out.push_back(p);
  };
  // Round shapes get rings (smooth surfaces at any radius); others a Cartesian lattice.
  const bool round = s.type == ShapeType::kCylinder || s.type == ShapeType::kDisc || s.type == ShapeType::kAnnulus;
  if (round) {
    const bool axis_y = s.type == ShapeType::kCylinder;
    const std::vector<double> axial = centred(0.5 * s.width, d0);
    for (double r = s.radius - 0.5 * d0; r > std::max(0.0, s.inner_radius); r -= d0) {
      const int nt = std::max(1, int(std::lround(2 * kPi * r / d0)));
      for (int k = 0; k < nt; ++k) {
        const double a = 2 * kPi * (k + 0.5) / nt;
        for (double h : axial)
          keep(axis_y ? Vec3<double>{r * std::cos(a), h, r * std::sin(a)}
                      : Vec3<double>{r * std::cos(a), r * std::sin(a), h});
      }
    }
    if (s.type == ShapeType::kCylinder && s.grouser_count > 0) {
      // Grousers: a lattice in each grouser's frame, outside the rim only (the rim has its rings).
      for (int g = 0; g < s.grouser_count; ++g) {
        const double a = 2 * kPi * g / s.grouser_count, ca = std::cos(a), sa = std::sin(a);
        for (double r = s.radius + 0.5 * d0; r < s.radius + s.grouser_height; r += d0)
          for (double t : centred(0.5 * s.grouser_thickness, d0))
            for (double y : axial) out.push_back({ca * r - sa * t, y, sa * r + ca * t});
      }
    }
    return out;
  }
  Vec3<double> ext = s.half_extents;
  if (s.type == ShapeType::kMesh) {
    Vec3<double> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    for (const auto& v : s.vertices)
      for (int q = 0; q < 3; ++q) {
        lo[q] = std::min(lo[q], v[q]);
        hi[q] = std::max(hi[q], v[q]);
      }
    // Lattice over the mesh bounds, aligned to d0 from the lower corner.
    for (double x = lo.x + 0.5 * d0; x < hi.x; x += d0)
      for (double y = lo.y + 0.5 * d0; y < hi.y; y += d0)
        for (double z = lo.z + 0.5 * d0; z < hi.z; z += d0) keep({x, y, z});
    return out;
  }
  for (double x : centred(ext.x, d0))
    for (double y : centred(ext.y, d0))
      for (double z : centred(ext.z, d0)) keep({x, y, z});
  return out;
}

Vec4<double> body_marker_normal(const BodyShape& s, const Vec3<double>& p, double d0) {
  const double depth = -shape_signed_distance(s, p);
  if (!(depth > 0)) return {0, 0, 0, 0};
  // Central differences of the distance field; the step is far below the spacing and far above
  // the rounding of the distance.
  const double e = 1e-4 * d0;
  Vec3<double> g{};
  for (int c = 0; c < 3; ++c) {
    Vec3<double> hi = p, lo = p;
    hi[c] += e;
    lo[c] -= e;
    g[c] = (shape_signed_distance(s, hi) - shape_signed_distance(s, lo)) / (2 * e);
  }
  const double len = norm(g);
  // Equally deep below two faces (the middle layer of a thin plate): a depth but no normal.
  if (!(len > 0.5)) return {0, 0, 0, depth};
  return {g.x / len, g.y / len, g.z / len, depth};
}

Vec4<double> bin_marker_normal(const CrmBin& bin, const Vec3<double>& p) {
  const Vec3<double> q{p.x < 0 ? -p.x : (p.x > bin.size.x ? bin.size.x - p.x : 0.0),
                       p.y < 0 ? -p.y : (p.y > bin.size.y ? bin.size.y - p.y : 0.0), p.z < 0 ? -p.z : 0.0};
  const double depth = norm(q);
  if (!(depth > 0)) return {0, 0, 0, 0};
  return {q.x / depth, q.y / depth, q.z / depth, depth};
}

std::vector<Vec3<double>> bin_marker_positions(const CrmBin& bin, double d0) {
  std::vector<Vec3<double>> out;
  const int L = bin.boundary_layers;
  const int nx = int(std::lround(bin.size.x / d0)), ny = int(std::lround(bin.size.y / d0));
  const int nz = int(std::ceil(bin.size.z / d0 - 1e-9));
  for (int k = -L; k < nz; ++k)
    for (int j = -L; j < ny + L; ++j)
      for (int i = -L; i < nx + L; ++i) {
        const bool inside = i >= 0 && i < nx && j >= 0 && j < ny && k >= 0;
        if (!inside) out.push_back({(i + 0.5) * d0, (j + 0.5) * d0, (k + 0.5) * d0});
      }
  return out;
}

}  // namespace terracal
