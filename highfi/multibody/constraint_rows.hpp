#pragma once
// Kinematic constraints as rows: the value Phi(q) and its Jacobian with respect to the two bodies'
// velocities (the linear velocity in the world frame, the angular velocity in the body frame), so that
// d/dt Phi = J_i [v_i; w_i] + J_j [v_j; w_j]. Joints are built from four primitives (as in the
// textbook of Haug): two points coincide, two directions are perpendicular (dot-1), a direction is
// perpendicular to the segment between two points (dot-2), and a distance.
#include <vector>

#include "highfi/multibody/rigid_body.hpp"

namespace terracal::mb {

using Row6 = Eigen::Matrix<double, 1, 6>;

struct ConstraintRow {
  double value = 0;
  int i = -1, j = -1;  // body indices into the system's list; a fixed body's part is dropped later
  Row6 ji = Row6::Zero(), jj = Row6::Zero();
};

// A point of each body (body-frame offsets): three rows, p_i - p_j = 0.
void rows_point(const RigidBody& bi, int i, const Vec3& si, const RigidBody& bj, int j, const Vec3& sj,
                std::vector<ConstraintRow>& out);
// A direction of each body (body-frame unit vectors): u_i . u_j = 0.
void row_perpendicular(const RigidBody& bi, int i, const Vec3& ai, const RigidBody& bj, int j, const Vec3& aj,
                       std::vector<ConstraintRow>& out);
// A direction a_i of body i is perpendicular to the segment from point s_i of body i to point s_j of
// body j: u_i . (p_j - p_i) = 0.
void row_dot2(const RigidBody& bi, int i, const Vec3& ai, const Vec3& si, const RigidBody& bj, int j, const Vec3& sj,
              std::vector<ConstraintRow>& out);
// The distance between two points is `length`: (d.d - L^2) / (2 L) = 0 (a length, like the others).
void row_distance(const RigidBody& bi, int i, const Vec3& si, const RigidBody& bj, int j, const Vec3& sj, double length,
                  std::vector<ConstraintRow>& out);

}  // namespace terracal::mb
