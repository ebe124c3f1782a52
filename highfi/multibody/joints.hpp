#pragma once
// Joints between two bodies, each a set of constraint rows (constraint_rows.hpp). A joint is placed
// like Chrono's: at a point of the world and with a frame whose z axis is the joint's axis (the
// revolute's hinge, the prismatic's slide, the line of a point-on-line joint), given in the assembled
// configuration; each body keeps that frame in its own coordinates.
#include <string>
#include <vector>

#include "highfi/multibody/constraint_rows.hpp"

namespace terracal::mb {

enum class JointType { revolute, spherical, universal, prismatic, fixed, distance, point_on_line, point_on_plane };

// The number of constraint rows of each type.
int joint_rows(JointType type);
const char* joint_type_name(JointType type);

struct Joint {
  std::string name;
  JointType type = JointType::spherical;
  int i = -1, j = -1;  // bodies (indices into the system's list)
  // The joint frame in each body: origin and axes (columns x, y, z), body coordinates.
  Vec3 si = Vec3::Zero(), sj = Vec3::Zero();
  Mat3 frame_i = Mat3::Identity(), frame_j = Mat3::Identity();
  double length = 0;  // distance joints: the distance held

  // A joint at `where` (world) with axes `axes` (world, columns x, y, z) between bodies i and j as they
  // are now. A universal joint's cross axes are x on body i and y on body j. A distance joint holds
  // the distance between `where` on body i and `other` on body j.
  static Joint place(std::string name, JointType type, const std::vector<RigidBody>& bodies, int i, int j,
                     const Vec3& where, const Mat3& axes = Mat3::Identity(), const Vec3& other = Vec3::Zero());

  // The same with a point of its own on each body (world, as the bodies are now): a distance joint's
  // two ends, or the point that a point-on-line or point-on-plane joint holds (on body j) apart from
  // the line's or plane's point (on body i).
  static Joint place_pair(std::string name, JointType type, const std::vector<RigidBody>& bodies, int i,
                          const Vec3& point_i, int j, const Vec3& point_j, const Mat3& axes = Mat3::Identity());

  void rows(const std::vector<RigidBody>& bodies, std::vector<ConstraintRow>& out) const;
};

}  // namespace terracal::mb
