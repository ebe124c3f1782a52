// Ray casts against body shapes: closed-form answers, agreement with the signed distance that
// defines each solid (highfi/crm/body_markers.cpp), and the BVH against a brute-force loop.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <map>
#include <random>

#include "core/shape_raycast.hpp"
#include "core/triangle_bvh.hpp"
#include "highfi/crm/body_markers.hpp"

using namespace terracal;
using V = Vec3<double>;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;

BodyShape box_shape() {
  BodyShape s;
  s.type = ShapeType::kBox;
  s.half_extents = {0.3, 0.2, 0.1};
  return s;
}
BodyShape wheel_shape(int grousers) {
  BodyShape s;
  s.type = ShapeType::kCylinder;
  s.radius = 0.25;
  s.width = 0.15;
  s.grouser_count = grousers;
  s.grouser_height = 0.02;
  s.grouser_thickness = 0.01;
  return s;
}
BodyShape plate_shape(ShapeType type) {
  BodyShape s;
  s.type = type;
  s.radius = 0.2;
  s.inner_radius = 0.1;
  s.width = 0.04;
  return s;
}

// A cube of half side h centred at c, two triangles per face.
BodyShape cube_mesh(double h, V c) {
  BodyShape s;
  s.type = ShapeType::kMesh;
  for (int i = 0; i < 8; ++i) s.vertices.push_back(c + V{(i & 1) ? h : -h, (i & 2) ? h : -h, (i & 4) ? h : -h});
  s.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return s;
}

// Icosahedron subdivided `levels` times (20 * 4^levels triangles), vertices pushed out to radius
// r * bump(direction): a closed, irregular, star-shaped mesh.
BodyShape icosphere(int levels, double r, bool bumpy) {
  const double p = (1 + std::sqrt(5.0)) / 2;
  std::vector<V> v = {{-1, p, 0},  {1, p, 0},  {-1, -p, 0}, {1, -p, 0}, {0, -1, p},  {0, 1, p},
                      {0, -1, -p}, {0, 1, -p}, {p, 0, -1},  {p, 0, 1},  {-p, 0, -1}, {-p, 0, 1}};
  std::vector<std::array<int, 3>> t = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mids;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = mids.find(key);
      if (it != mids.end()) return it->second;
      v.push_back(0.5 * (v[std::size_t(a)] + v[std::size_t(b)]));
      return mids[key] = int(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& f : t) {
      const int a = mid(f[0], f[1]), b = mid(f[1], f[2]), c = mid(f[2], f[0]);
      next.insert(next.end(), {{f[0], a, c}, {f[1], b, a}, {f[2], c, b}, {a, b, c}});
    }
    t = next;
  }
  BodyShape s;
  s.type = ShapeType::kMesh;
  for (V q : v) {
    q = (1 / norm(q)) * q;
    const double bump = bumpy ? 1 + 0.15 * std::sin(5 * q.x) * std::cos(3 * q.y + q.z) : 1.0;
    s.vertices.push_back((r * bump) * q);
  }
  s.triangles = t;
  return s;
}

// Brute force over all triangles, Möller–Trumbore exactly as the BVH's leaves do it.
double brute_first_hit(const BodyShape& s, V o, V d, double t_max) {
  double best = kInf;
  for (const auto& tri : s.triangles) {
    const V v0 = s.vertices[std::size_t(tri[0])];
    const V e1 = s.vertices[std::size_t(tri[1])] - v0, e2 = s.vertices[std::size_t(tri[2])] - v0;
    const V p = cross(d, e2);
    const double det = dot(e1, p);
    if (det == 0) continue;
    const double inv_det = 1.0 / det;
    const V tv = o - v0;
    const double u = dot(tv, p) * inv_det;
    if (u < 0 || u > 1) continue;
    const V q = cross(tv, e1);
    const double w = dot(d, q) * inv_det;
    if (w < 0 || u + w > 1) continue;
    const double t = dot(e2, q) * inv_det;
    if (t >= 0 && t <= t_max) best = std::min(best, t);
  }
  return best;
}

// True when no point of o + t d, t in [0, t_end - ~1e-7 scale), is inside the solid by more than
// tol. The samples are sphere-traced: each step is the signed distance itself (a lower bound on the
// distance to the solid from outside), never less than 1e-7 scale, so no piece of solid thicker
// than that can lie between two samples.
bool segment_outside(const BodyShape& s, V o, V d, double t_end, double scale, double tol) {
  const double dn = norm(d), floor_t = 1e-7 * scale / dn;
  double t = 0;
  for (int step = 0; t < t_end - floor_t; ++step) {
    const double sd = shape_signed_distance(s, o + t * d);
    if (sd < -tol) return false;
    if (step > 2000000) return false;  // only a ray grazing a face within 1e-7 for its whole length
    t += std::max(sd / dn, floor_t);
  }
  return true;
}

V random_in(std::mt19937_64& rng, V lo, V hi) {
  std::uniform_real_distribution<double> u(0, 1);
  return {lo.x + u(rng) * (hi.x - lo.x), lo.y + u(rng) * (hi.y - lo.y), lo.z + u(rng) * (hi.z - lo.z)};
}

// Casts n random rays and checks each answer against shape_signed_distance. Origins in a box around
// the bounds (outside the bounds only for meshes, whose inside the caster does not detect); most
// rays aim at a point of the bounds, a quarter are axis-aligned like the SCM's vertical rays.
void check_against_sdf(const BodyShape& s, int n, std::uint64_t seed) {
  const ShapeRaycaster rc(s);
  const V lo = rc.bounds_lo(), hi = rc.bounds_hi();
  const double scale = norm(hi - lo), tol = 1e-9 * scale;
  const V c = 0.5 * (lo + hi), pad{scale, scale, scale};
  const bool mesh = s.type == ShapeType::kMesh;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  int hits = 0, misses = 0, inside = 0;
  for (int i = 0; i < n; ++i) {
    V o = random_in(rng, lo - pad, hi + pad);
    if (i % 8 == 1) o = random_in(rng, lo, hi);               // often inside the solid
    if (mesh) o = c + (1.2 * scale / norm(o - c)) * (o - c);  // outside the mesh's bounding sphere
    V d = random_in(rng, lo, hi) - o;
    if (i % 4 == 0) {  // axis-aligned, either sign
      const int k = int(u(rng) * 3);
      d = V{};
      d[k] = u(rng) < 0.5 ? -1 : 1;
    }
    d = (0.5 + 1.5 * u(rng)) / norm(d) * d;  // not unit: t must scale with |d|
    const double t_max = 4 * scale / norm(d);
    const double t = rc.first_hit(o, d, t_max);
    INFO("shape " << int(s.type) << " ray " << i << " o " << o.x << " " << o.y << " " << o.z << " d " << d.x << " "
                  << d.y << " " << d.z << " t " << t);
    if (t == kInf) {
      ++misses;
      REQUIRE(segment_outside(s, o, d, t_max, scale, tol));
    } else if (t == 0 && !mesh) {
      ++inside;
      REQUIRE(shape_signed_distance(s, o) <= tol);
    } else {
      ++hits;
      REQUIRE(t > 0);
      REQUIRE(t <= t_max);
      REQUIRE(std::abs(shape_signed_distance(s, o + t * d)) < tol);
      REQUIRE(segment_outside(s, o, d, t, scale, tol));
    }
  }
  // The sample must exercise every branch to mean anything.
  CHECK(hits > n / 4);
  CHECK(misses > n / 50);
  if (!mesh) CHECK(inside > 0);
}

}  // namespace

TEST_CASE("ShapeRaycaster: closed-form hits on box, cylinder, disc and annulus", "[core][raycast]") {
  const V up{0, 0, 1};
  {
    const ShapeRaycaster box(box_shape());
    CHECK(box.first_hit({0.1, 0.05, -1}, up, 10) == Approx(0.9).margin(1e-12));         // z = -half_z
    CHECK(box.first_hit({0.1, 0.05, -1}, 2.0 * up, 10) == Approx(0.45).margin(1e-12));  // |dir| = 2
    CHECK(box.first_hit({0.31, 0.05, -1}, up, 10) == kInf);                             // beside it
    CHECK(box.first_hit({0.1, 0.05, -1}, up, 0.8) == kInf);                             // too short
    CHECK(box.first_hit({0.1, 0.05, 0}, up, 10) == 0);                                  // inside
    CHECK(box.first_hit({0.1, 0.05, -1}, -1.0 * up, 10) == kInf);                       // pointing away
    CHECK(box.bounds_lo().z == -0.1);
    CHECK(box.bounds_hi().x == 0.3);
  }
  {
    const BodyShape s = wheel_shape(0);
    const ShapeRaycaster cyl(s);
    const double dx = 0.1;
    CHECK(cyl.first_hit({dx, 0.02, -1}, up, 10) - 1 == Approx(-std::sqrt(s.radius * s.radius - dx * dx)).margin(1e-12));
    CHECK(cyl.first_hit({dx, 0.08, -1}, up, 10) == kInf);                                     // beyond width / 2
    CHECK(cyl.first_hit({0.1, -1, 0.05}, {0, 1, 0}, 10) == Approx(1 - 0.075).margin(1e-12));  // end face
  }
  {
    const ShapeRaycaster disc(plate_shape(ShapeType::kDisc)), ann(plate_shape(ShapeType::kAnnulus));
    CHECK(disc.first_hit({0.05, 0.02, -1}, up, 10) == Approx(1 - 0.02).margin(1e-12));
    CHECK(disc.first_hit({-1, 0.03, 0.01}, {1, 0, 0}, 10) - 1 == Approx(-std::sqrt(0.04 - 0.03 * 0.03)).margin(1e-12));
    CHECK(ann.first_hit({0.05, 0.02, -1}, up, 10) == kInf);  // through the hole
    CHECK(ann.first_hit({0.15, 0.0, -1}, up, 10) == Approx(1 - 0.02).margin(1e-12));
    CHECK(ann.first_hit({-1, 0, 0}, {1, 0, 0}, 10) == Approx(0.8).margin(1e-12));  // outer rim
    CHECK(ann.first_hit({0, 0, 0}, {1, 0, 0}, 10) == Approx(0.1).margin(1e-12));   // from the hole
    CHECK(ann.first_hit({0.15, 0, 0}, {1, 0, 0}, 10) == 0);                        // inside
    CHECK(ann.first_hit({0, 0, 0}, {1, 0, 0}, 0.09) == kInf);
  }
}

TEST_CASE("ShapeRaycaster: grouser tips stand out of the rim", "[core][raycast]") {
  const BodyShape s = wheel_shape(12);
  const ShapeRaycaster w(s);
  const double R = s.radius, h = s.grouser_height, th = s.grouser_thickness;
  // Grouser 9 of 12 sits at 2 pi 9 / 12 = 3 pi / 2: radial = -z, pointing straight down.
  CHECK(w.first_hit({0, 0, -1}, {0, 0, 1}, 10) - 1 == Approx(-(R + h)).margin(1e-12));
  CHECK(w.first_hit({0.45 * th, 0.07, -1}, {0, 0, 1}, 10) - 1 == Approx(-(R + h)).margin(1e-12));
  // Beside the grouser (tangential offset > th / 2) the ray reaches the rim.
  CHECK(w.first_hit({th, 0, -1}, {0, 0, 1}, 10) - 1 == Approx(-std::sqrt(R * R - th * th)).margin(1e-12));
  // Grouser 0 points along +x: a ray coming in along -x meets its tip at x = R + h.
  CHECK(w.first_hit({1, 0, 0}, {-1, 0, 0}, 10) == Approx(1 - (R + h)).margin(1e-12));
  // The bounds include the grouser tips.
  CHECK(w.bounds_hi().x == Approx(R + h).margin(1e-12));
  CHECK(w.bounds_lo().z == Approx(-(R + h)).margin(1e-12));
  CHECK(w.bounds_hi().y == Approx(0.5 * s.width));
}

TEST_CASE("ShapeRaycaster: random rays agree with shape_signed_distance", "[core][raycast]") {
  SECTION("box") { check_against_sdf(box_shape(), 3000, 1); }
  SECTION("cylinder") { check_against_sdf(wheel_shape(0), 3000, 2); }
  SECTION("wheel with 12 grousers") { check_against_sdf(wheel_shape(12), 3000, 3); }
  SECTION("wheel with 30 thick grousers") {  // other proportions for the grouser culling
    BodyShape s = wheel_shape(30);
    s.grouser_thickness = 0.04;
    s.grouser_height = 0.05;
    check_against_sdf(s, 3000, 8);
  }
  SECTION("disc") { check_against_sdf(plate_shape(ShapeType::kDisc), 3000, 4); }
  SECTION("annulus") { check_against_sdf(plate_shape(ShapeType::kAnnulus), 3000, 5); }
  SECTION("cube mesh") { check_against_sdf(cube_mesh(0.2, {0.05, -0.02, 0.01}), 2000, 6); }
  SECTION("bumpy icosphere mesh") { check_against_sdf(icosphere(1, 0.3, true), 2000, 7); }
}

TEST_CASE("TriangleBvh: same first hit as brute force on a 1280-triangle mesh", "[core][raycast]") {
  const BodyShape s = icosphere(3, 0.5, true);
  REQUIRE(s.triangles.size() >= 1000);
  const TriangleBvh bvh(s.vertices, s.triangles);
  REQUIRE(!bvh.empty());
  CHECK(TriangleBvh().empty());
  CHECK(TriangleBvh().first_hit({0, 0, -1}, {0, 0, 1}, 10) == kInf);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  int hits = 0;
  const int n = 5000;
  for (int i = 0; i < n; ++i) {
    // Origins inside and outside the mesh; random and axis-aligned directions; t_max that sometimes
    // stops short of the surface.
    const V o = random_in(rng, {-1, -1, -1}, {1, 1, 1});
    V d = random_in(rng, {-0.6, -0.6, -0.6}, {0.6, 0.6, 0.6}) - o;
    if (i % 3 == 0) {
      d = V{};
      d[i % 9 / 3] = u(rng) < 0.5 ? -0.7 : 1.3;
    }
    const double t_max = 3 * u(rng);
    const double expect = brute_first_hit(s, o, d, t_max), got = bvh.first_hit(o, d, t_max);
    INFO("ray " << i);
    REQUIRE((got == kInf) == (expect == kInf));
    if (expect != kInf) {
      ++hits;
      REQUIRE(got == Approx(expect).margin(1e-12));
    }
  }
  CHECK(hits > n / 4);
}
