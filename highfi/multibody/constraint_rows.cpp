#include "highfi/multibody/constraint_rows.hpp"

namespace terracal::mb {
namespace {
Row6 lin_ang(const Vec3& lin, const Vec3& ang) {
  Row6 r;
  r << lin.transpose(), ang.transpose();
  return r;
}
}  // namespace

void rows_point(const RigidBody& bi, int i, const Vec3& si, const RigidBody& bj, int j, const Vec3& sj,
                std::vector<ConstraintRow>& out) {
  const Vec3 d = bi.point(si) - bj.point(sj);
  // d/dt p = v + A (w x s) = v - A skew(s) w.
  const Eigen::Matrix3d wi = -bi.rotation() * skew(si), wj = -bj.rotation() * skew(sj);
  for (int k = 0; k < 3; ++k) {
    ConstraintRow r;
    r.value = d[k];
    r.i = i;
    r.j = j;
    r.ji = lin_ang(Vec3::Unit(k), wi.row(k).transpose());
    r.jj = -lin_ang(Vec3::Unit(k), wj.row(k).transpose());
    out.push_back(r);
  }
}

void row_perpendicular(const RigidBody& bi, int i, const Vec3& ai, const RigidBody& bj, int j, const Vec3& aj,
                       std::vector<ConstraintRow>& out) {
  const Vec3 ui = bi.rotation() * ai, uj = bj.rotation() * aj;
  // d/dt u_i = A_i (w_i x a_i), and u_j . A_i (w_i x a_i) = w_i . (a_i x A_i^T u_j).
  ConstraintRow r;
  r.value = ui.dot(uj);
  r.i = i;
  r.j = j;
  r.ji = lin_ang(Vec3::Zero(), ai.cross(bi.rotation().transpose() * uj));
  r.jj = lin_ang(Vec3::Zero(), aj.cross(bj.rotation().transpose() * ui));
  out.push_back(r);
}

void row_dot2(const RigidBody& bi, int i, const Vec3& ai, const Vec3& si, const RigidBody& bj, int j, const Vec3& sj,
              std::vector<ConstraintRow>& out) {
  const Mat3 Ai = bi.rotation(), Aj = bj.rotation();
  const Vec3 ui = Ai * ai, d = bj.point(sj) - bi.point(si);
  ConstraintRow r;
  r.value = ui.dot(d);
  r.i = i;
  r.j = j;
  // d/dt (u_i . d) = w_i . (a_i x A_i^T d) + u_i . (v_j - v_i) + w_j . (s_j x A_j^T u_i) - w_i . (s_i x A_i^T u_i).
  r.ji = lin_ang(-ui, ai.cross(Ai.transpose() * d) - si.cross(Ai.transpose() * ui));
  r.jj = lin_ang(ui, sj.cross(Aj.transpose() * ui));
  out.push_back(r);
}

void row_distance(const RigidBody& bi, int i, const Vec3& si, const RigidBody& bj, int j, const Vec3& sj, double length,
                  std::vector<ConstraintRow>& out) {
  const Mat3 Ai = bi.rotation(), Aj = bj.rotation();
  const Vec3 d = bj.point(sj) - bi.point(si);
  ConstraintRow r;
  r.value = (d.squaredNorm() - length * length) / (2 * length);
  r.i = i;
  r.j = j;
  // d/dt of it: d . (p_j' - p_i') / L.
  r.ji = -lin_ang(d, si.cross(Ai.transpose() * d)) / length;
  r.jj = lin_ang(d, sj.cross(Aj.transpose() * d)) / length;
  out.push_back(r);
}

}  // namespace terracal::mb
