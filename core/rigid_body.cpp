#include "core/rigid_body.hpp"

#include <algorithm>
#include <cmath>

namespace terracal {

bool BodyMotion::moves() const { return any_free() || max_speed(1.0) > 0; }
Vec3<double> BodyMotion::linear_at(double t) const {
  if (schedule.empty()) return linear_velocity;
  double end = 0;
  for (const auto& seg : schedule)
    if (t < (end += seg.duration)) return seg.linear_velocity;
  return {};
}
Vec3<double> BodyMotion::angular_at(double t) const {
  if (schedule.empty()) return angular_velocity;
  double end = 0;
  for (const auto& seg : schedule)
    if (t < (end += seg.duration)) return seg.angular_velocity;
  return {};
}
double BodyMotion::max_speed(double radius) const {
  double v = norm(linear_velocity) + norm(angular_velocity) * radius;
  for (const auto& seg : schedule) v = std::max(v, norm(seg.linear_velocity) + norm(seg.angular_velocity) * radius);
  return v;
}
bool BodyMotion::any_free() const {
  for (bool f : free)
    if (f) return true;
  return false;
}

double RigidBody::bounding_radius() const {
  switch (shape.type) {
    case ShapeType::kBox:
      return norm(shape.half_extents);
    case ShapeType::kCylinder:
      return std::hypot(shape.radius + shape.grouser_height, 0.5 * shape.width);
    case ShapeType::kDisc:
    case ShapeType::kAnnulus:
      return std::hypot(shape.radius, 0.5 * shape.width);
    case ShapeType::kMesh: {
      double r = 0;
      for (const auto& v : shape.vertices) r = std::max(r, norm(v));
      return r;
    }
  }
  return 0;
}

BodyState advance_body(const RigidBody& body, const BodyState& base, const BodyState& at, const BodyWrench& w,
                       const Vec3<double>& gravity, double h, double t_out) {
  BodyState out = base;
  out.position = base.position + h * at.velocity;
  out.orientation = integrate_rotation(base.orientation, at.omega, h);
  const auto& f = body.motion.free;
  if (!body.motion.schedule.empty()) {
    const Vec3<double> v = body.motion.linear_at(t_out), w_ = body.motion.angular_at(t_out);
    for (int q = 0; q < 3; ++q) {
      if (!f[q]) out.velocity[q] = v[q];
      if (!f[3 + q]) out.omega[q] = w_[q];
    }
  }
  if (f[0] || f[1] || f[2]) {
    const double k = body.load_fraction(t_out);
    const Vec3<double> a = (1.0 / body.mass) * (w.force + k * body.applied_force) + k * gravity;
    for (int q = 0; q < 3; ++q)
      if (f[q]) out.velocity[q] = base.velocity[q] + h * a[q];
  }
  if (f[3] || f[4] || f[5]) {
    // Euler's equations in the world frame: I_w domega/dt = tau - omega x I_w omega, I_w = R I R^T.
    double R[9];
    at.orientation.to_matrix(R);
    auto body_to_world_inertia = [&](const Vec3<double>& v) {  // I_w v
      const Vec3<double> vb{R[0] * v.x + R[3] * v.y + R[6] * v.z, R[1] * v.x + R[4] * v.y + R[7] * v.z,
                            R[2] * v.x + R[5] * v.y + R[8] * v.z};
      const Vec3<double> ib{body.inertia.x * vb.x, body.inertia.y * vb.y, body.inertia.z * vb.z};
      return Vec3<double>{R[0] * ib.x + R[1] * ib.y + R[2] * ib.z, R[3] * ib.x + R[4] * ib.y + R[5] * ib.z,
                          R[6] * ib.x + R[7] * ib.y + R[8] * ib.z};
    };
    const Vec3<double> rhs = w.torque + body.applied_torque - cross(at.omega, body_to_world_inertia(at.omega));
    // I_w^{-1} rhs = R I^{-1} R^T rhs
    const Vec3<double> rb{R[0] * rhs.x + R[3] * rhs.y + R[6] * rhs.z, R[1] * rhs.x + R[4] * rhs.y + R[7] * rhs.z,
                          R[2] * rhs.x + R[5] * rhs.y + R[8] * rhs.z};
    const Vec3<double> ab{rb.x / body.inertia.x, rb.y / body.inertia.y, rb.z / body.inertia.z};
    const Vec3<double> alpha{R[0] * ab.x + R[1] * ab.y + R[2] * ab.z, R[3] * ab.x + R[4] * ab.y + R[5] * ab.z,
                             R[6] * ab.x + R[7] * ab.y + R[8] * ab.z};
    for (int q = 0; q < 3; ++q)
      if (f[3 + q]) out.omega[q] = base.omega[q] + h * alpha[q];
  }
  return out;
}

}  // namespace terracal
