#pragma once
// A rigid body in maximal coordinates: the position of its centre of mass and its orientation
// (a unit quaternion, body to world) in the world frame; its linear velocity in the world frame and its
// angular velocity in its own frame (where its inertia tensor is constant). A fixed body (the ground)
// has no coordinates in the system's state.
#include <string>

#include <Eigen/Dense>
#include <Eigen/Geometry>

namespace terracal::mb {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

struct RigidBody {
  std::string name;
  double mass = 1;                  // kg
  Mat3 inertia = Mat3::Identity();  // about the centre of mass, in the body frame, kg m^2
  Vec3 position = Vec3::Zero();     // centre of mass, world, m
  Quat orientation = Quat::Identity();
  Vec3 velocity = Vec3::Zero();  // world, m/s
  Vec3 omega = Vec3::Zero();     // body frame, rad/s
  bool fixed = false;

  Mat3 rotation() const { return orientation.toRotationMatrix(); }
  // A point given in the body frame, in the world frame.
  Vec3 point(const Vec3& local) const { return position + rotation() * local; }
  // The velocity of that point, world frame.
  Vec3 point_velocity(const Vec3& local) const { return velocity + rotation() * omega.cross(local); }
};

// The skew matrix of v: skew(v) w = v x w.
inline Mat3 skew(const Vec3& v) {
  Mat3 s;
  s << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return s;
}

}  // namespace terracal::mb
