#pragma once
// Compares the integrator's sparse Newton matrix with central differences of the whole GGL residual,
// at a state with the given velocities' spread and multipliers lambda, and mu = 0 (the matrix leaves
// out only terms proportional to mu): the largest error of a row relative to that row's largest entry
// (or 1, when smaller), and where it is.
#include <algorithm>
#include <cmath>
#include <random>

#include "highfi/multibody/ggl_jacobian.hpp"
#include "highfi/multibody/ggl_residual.hpp"

namespace terracal::test {

struct JacobianError {
  double error = 0;
  int row = -1, column = -1;
  double ours = 0, reference = 0;
};

inline JacobianError ggl_jacobian_error(mb::MbSystem& s, double t, double speed_spread, double lambda_spread, double cj = 1e3,
                                 unsigned seed = 7) {
  using Eigen::VectorXd;
  const int n = mb::ggl_size(s), nq = s.coordinates(), nu = s.velocities(), m = s.constraint_rows();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1, 1);
  VectorXd y = VectorXd::Zero(n), yp(n);
  s.get_positions(y.data());
  s.get_velocities(y.data() + nq);
  for (int k = nq; k < nq + nu; ++k) y[k] += speed_spread * unit(rng);
  for (int k = nq + nu; k < nq + nu + m; ++k) y[k] = lambda_spread * unit(rng);
  for (int k = 0; k < n; ++k) yp[k] = unit(rng);
  const Eigen::MatrixXd mass = s.mass_matrix();
  mb::GglJacobian jacobian(s);
  const Eigen::MatrixXd ours = Eigen::MatrixXd(jacobian.evaluate(t, y.data(), cj));
  Eigen::MatrixXd reference(n, n);
  VectorXd rp(n), rm(n);
  for (int c = 0; c < n; ++c) {
    const double h = 1e-6 * std::max(1.0, std::abs(y[c]));
    VectorXd a = y, b = y, ap = yp, bp = yp;
    a[c] += h, ap[c] += cj * h;
    b[c] -= h, bp[c] -= cj * h;
    mb::ggl_residual(s, mass, t, a.data(), ap.data(), rp.data());
    mb::ggl_residual(s, mass, t, b.data(), bp.data(), rm.data());
    reference.col(c) = (rp - rm) / (2 * h);
  }
  JacobianError worst;
  for (int r = 0; r < n; ++r) {
    const double scale = std::max(1.0, reference.row(r).lpNorm<Eigen::Infinity>());
    for (int c = 0; c < n; ++c)
      if (std::abs(ours(r, c) - reference(r, c)) / scale > worst.error)
        worst = {std::abs(ours(r, c) - reference(r, c)) / scale, r, c, ours(r, c), reference(r, c)};
  }
  return worst;
}

}  // namespace terracal::test
