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

  void rows(const std::vector<RigidBody>& bodies, std::vector<ConstraintRow>& out) const;
};

}  // namespace terracal::mb
