#pragma once
// Force elements between two bodies. Each adds to the bodies' applied wrenches: a force in the world
// frame and a torque in the body's own frame (where the equations of motion take it).
#include <functional>
#include <string>
#include <vector>

#include "highfi/multibody/rigid_body.hpp"

namespace terracal::mb {

struct Wrench {
  Vec3 force = Vec3::Zero();   // world
  Vec3 torque = Vec3::Zero();  // body frame
};

// A restoring force (or torque) as a function of a deflection (or angle) and its rate: a table, or
// f0 + k x + c v. Positive resists a positive deflection.
using ForceLaw = std::function<double(double deflection, double rate)>;
ForceLaw linear_law(double stiffness, double damping, double at_zero = 0);
// Tabulated: force against deflection plus force against rate (piecewise linear, extended linearly
// past the ends, as springs with bump stops are measured). x values increase.
ForceLaw table_law(std::vector<double> defl, std::vector<double> force, std::vector<double> rate,
                   std::vector<double> damper_force);

// Translational spring-damper between a point of body i and a point of body j: the law gives the
// tension (positive pulls the points together) for the deflection, length - rest length, and the
// length's rate.
struct SpringDamper {
  std::string name;
  int i = -1, j = -1;
  Vec3 si = Vec3::Zero(), sj = Vec3::Zero();  // body frames
  double rest_length = 0;
  ForceLaw law;  // tension
  double length(const std::vector<RigidBody>& b) const;
  void apply(const std::vector<RigidBody>& b, std::vector<Wrench>& w) const;
};

// Rotational spring-damper about body i's axis z (its frame in body i; body j's frame gives the
// angle's zero): the law gives the torque that turns j back, for the angle of j about that axis and
// its rate.
struct RotationalSpringDamper {
  std::string name;
  int i = -1, j = -1;
  Mat3 frame_i = Mat3::Identity(), frame_j = Mat3::Identity();  // body frames, columns x, y, z
  ForceLaw law;
  double angle(const std::vector<RigidBody>& b) const;
  void apply(const std::vector<RigidBody>& b, std::vector<Wrench>& w) const;
};

// A bushing: linear springs and dampers on the small relative translation and rotation of a frame of
// body j against a frame of body i (both at the same point when assembled), in body i's frame.
struct Bushing {
  std::string name;
  int i = -1, j = -1;
  Vec3 si = Vec3::Zero(), sj = Vec3::Zero();
  Mat3 frame_i = Mat3::Identity(), frame_j = Mat3::Identity();
  Vec3 k_lin = Vec3::Zero(), c_lin = Vec3::Zero();  // N/m, N s/m along the frame's axes
  Vec3 k_rot = Vec3::Zero(), c_rot = Vec3::Zero();  // N m/rad, N m s/rad
  void apply(const std::vector<RigidBody>& b, std::vector<Wrench>& w) const;
};

// Applies a world force at a body-frame point of body b.
void add_force_at(const RigidBody& body, const Vec3& local, const Vec3& force, Wrench& w);

}  // namespace terracal::mb
