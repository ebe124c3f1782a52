#include "highfi/multibody/joints.hpp"

namespace terracal::mb {

int joint_rows(JointType type) {
  switch (type) {
    case JointType::revolute:
      return 5;
    case JointType::spherical:
      return 3;
    case JointType::universal:
      return 4;
    case JointType::prismatic:
      return 5;
    case JointType::fixed:
      return 6;
    case JointType::distance:
      return 1;
    case JointType::point_on_line:
      return 2;
    case JointType::point_on_plane:
      return 1;
  }
  return 0;
}

const char* joint_type_name(JointType type) {
  switch (type) {
    case JointType::revolute:
      return "revolute";
    case JointType::spherical:
      return "spherical";
    case JointType::universal:
      return "universal";
    case JointType::prismatic:
      return "prismatic";
    case JointType::fixed:
      return "fixed";
    case JointType::distance:
      return "distance";
    case JointType::point_on_line:
      return "point_on_line";
    case JointType::point_on_plane:
      return "point_on_plane";
  }
  return "?";
}

Joint Joint::place(std::string name, JointType type, const std::vector<RigidBody>& bodies, int i, int j,
                   const Vec3& where, const Mat3& axes, const Vec3& other) {
  return place_pair(std::move(name), type, bodies, i, where, j, type == JointType::distance ? other : where, axes);
}

Joint Joint::place_pair(std::string name, JointType type, const std::vector<RigidBody>& bodies, int i,
                        const Vec3& point_i, int j, const Vec3& point_j, const Mat3& axes) {
  Joint jt;
  jt.name = std::move(name);
  jt.type = type;
  jt.i = i;
  jt.j = j;
  const RigidBody &bi = bodies.at(std::size_t(i)), &bj = bodies.at(std::size_t(j));
  jt.si = bi.rotation().transpose() * (point_i - bi.position);
  jt.frame_i = bi.rotation().transpose() * axes;
  jt.sj = bj.rotation().transpose() * (point_j - bj.position);
  jt.frame_j = bj.rotation().transpose() * axes;
  jt.length = (point_j - point_i).norm();
  return jt;
}

void Joint::rows(const std::vector<RigidBody>& b, std::vector<ConstraintRow>& out) const {
  const RigidBody &bi = b[std::size_t(i)], &bj = b[std::size_t(j)];
  const Vec3 xi = frame_i.col(0), yi = frame_i.col(1), zi = frame_i.col(2);
  const Vec3 xj = frame_j.col(0), yj = frame_j.col(1);
  switch (type) {
    case JointType::spherical:
      rows_point(bi, i, si, bj, j, sj, out);
      break;
    case JointType::revolute:  // the point, and body i's axis z stays normal to body j's x and y
      rows_point(bi, i, si, bj, j, sj, out);
      row_perpendicular(bi, i, zi, bj, j, xj, out);
      row_perpendicular(bi, i, zi, bj, j, yj, out);
      break;
    case JointType::universal:  // the point, and the cross: x on body i stays normal to y on body j
      rows_point(bi, i, si, bj, j, sj, out);
      row_perpendicular(bi, i, xi, bj, j, yj, out);
      break;
    case JointType::fixed:
      rows_point(bi, i, si, bj, j, sj, out);
      row_perpendicular(bi, i, zi, bj, j, xj, out);
      row_perpendicular(bi, i, zi, bj, j, yj, out);
      row_perpendicular(bi, i, xi, bj, j, yj, out);
      break;
    case JointType::prismatic:  // axes kept, no turn about z, and the points only apart along z
      row_perpendicular(bi, i, zi, bj, j, xj, out);
      row_perpendicular(bi, i, zi, bj, j, yj, out);
      row_perpendicular(bi, i, xi, bj, j, yj, out);
      row_dot2(bi, i, xi, si, bj, j, sj, out);
      row_dot2(bi, i, yi, si, bj, j, sj, out);
      break;
    case JointType::point_on_line:  // body j's point stays on body i's line (through s_i along z)
      row_dot2(bi, i, xi, si, bj, j, sj, out);
      row_dot2(bi, i, yi, si, bj, j, sj, out);
      break;
    case JointType::point_on_plane:  // body j's point stays on body i's plane (through s_i, normal z)
      row_dot2(bi, i, zi, si, bj, j, sj, out);
      break;
    case JointType::distance:
      row_distance(bi, i, si, bj, j, sj, length, out);
      break;
  }
}

}  // namespace terracal::mb
