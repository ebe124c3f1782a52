#include "highfi/multibody/shafts.hpp"

#include <algorithm>

namespace terracal::mb {

ShaftLinkage gear(std::string name, int in, int out, double ratio) {
  return {std::move(name), {out, in}, {1.0, -ratio}};
}

ShaftLinkage differential(std::string name, int case_shaft, int left, int right) {
  return {std::move(name), {left, right, case_shaft}, {1.0, 1.0, -2.0}};
}

ConstraintRow ShaftToBody::row(const std::vector<RigidBody>& b, Row6& shaft_part) const {
  const RigidBody &bi = b[std::size_t(i)], &bj = b[std::size_t(j)];
  const Vec3 z = bi.rotation() * axis_i;
  ConstraintRow r;
  r.i = i;
  r.j = j;
  // w_s - z . (A_j w_j - A_i w_i) = 0, with z . A_i w_i = axis_i . w_i.
  r.ji.tail<3>() = axis_i.transpose();  // the row's sign: -(-z . A_i w_i)
  r.jj.tail<3>() = -(bj.rotation().transpose() * z).transpose();
  shaft_part.setZero();
  shaft_part[0] = 1;
  return r;
}

double Clutch::torque(double wa, double wb) const {
  return std::clamp(slip_damping * (wa - wb), -max_torque, max_torque);
}

}  // namespace terracal::mb
