#pragma once
// Unit quaternions (w, x, y, z) for rigid-body orientation, in double precision on the host.
#include <cmath>

#include "core/vec.hpp"

namespace terracal {

struct Quat {
  double w = 1, x = 0, y = 0, z = 0;

  static Quat from_axis_angle(Vec3<double> axis, double angle) {
    const double n = norm(axis);
    if (n == 0.0 || angle == 0.0) return {};
    const double s = std::sin(0.5 * angle) / n;
    return {std::cos(0.5 * angle), axis.x * s, axis.y * s, axis.z * s};
  }
  Quat normalized() const {
    const double n = std::sqrt(w * w + x * x + y * y + z * z);
    return {w / n, x / n, y / n, z / n};
  }
  // Row-major rotation matrix.
  void to_matrix(double R[9]) const {
    R[0] = 1 - 2 * (y * y + z * z);
    R[1] = 2 * (x * y - w * z);
    R[2] = 2 * (x * z + w * y);
    R[3] = 2 * (x * y + w * z);
    R[4] = 1 - 2 * (x * x + z * z);
    R[5] = 2 * (y * z - w * x);
    R[6] = 2 * (x * z - w * y);
    R[7] = 2 * (y * z + w * x);
    R[8] = 1 - 2 * (x * x + y * y);
  }
  Vec3<double> rotate(Vec3<double> v) const {
    double R[9];
    to_matrix(R);
    return {R[0] * v.x + R[1] * v.y + R[2] * v.z, R[3] * v.x + R[4] * v.y + R[5] * v.z,
            R[6] * v.x + R[7] * v.y + R[8] * v.z};
  }
};

inline Quat operator*(const Quat& a, const Quat& b) {
  return {a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z, a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
          a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x, a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}

// Orientation after turning at world angular velocity omega for dt (exact for constant omega).
inline Quat integrate_rotation(const Quat& q, Vec3<double> omega, double dt) {
  const double rate = norm(omega);
  if (rate * dt == 0.0) return q;
  return (Quat::from_axis_angle(omega, rate * dt) * q).normalized();
}

}  // namespace terracal
