#include "highfi/multibody/ggl_residual.hpp"

namespace terracal::mb {

bool ggl_residual(MbSystem& s, const Eigen::MatrixXd& mass, double t, const double* y, const double* ydot, double* r) {
  using Eigen::VectorXd;
  const int nq = s.coordinates(), nu = s.velocities(), m = s.constraint_rows(), mh = s.position_rows(), nb = s.moving();
  const Eigen::Map<const VectorXd> q(y, nq), u(y + nq, nu), lambda(y + nq + nu, m), mu(y + nq + nu + m, mh + nb);
  s.set_positions(q.data());
  s.set_velocities(u.data());
  VectorXd phi;
  Eigen::MatrixXd jac;
  s.constraints(phi, jac);
  const VectorXd f = s.applied(t);
  const VectorXd corrected = u + jac.topRows(mh).transpose() * mu.head(mh);
  VectorXd qdot(nq);
  s.coordinate_rates(q.data(), corrected.data(), qdot.data());
  for (int k = 0; k < nb; ++k) qdot.segment<4>(7 * k + 3) += q.segment<4>(7 * k + 3) * mu[mh + k];
  Eigen::Map<VectorXd> rq(r, nq), ru(r + nq, nu), rphi(r + nq + nu, mh + nb), rvel(r + nq + nu + mh + nb, m);
  rq = Eigen::Map<const VectorXd>(ydot, nq) - qdot;
  ru = mass * Eigen::Map<const VectorXd>(ydot + nq, nu) - f + jac.transpose() * lambda;
  rphi.head(mh) = phi;
  for (int k = 0; k < nb; ++k) rphi[mh + k] = 0.5 * (q.segment<4>(7 * k + 3).squaredNorm() - 1);
  rvel = jac * u;
  return phi.allFinite() && f.allFinite();
}

}  // namespace terracal::mb
