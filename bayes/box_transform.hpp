#pragma once
// A target over a box of bounds seen in unbounded coordinates: x_j = lower_j + (upper_j - lower_j)
// / (1 + exp(-u_j)). A posterior that fills its prior's box, or leans against one side of it, is far
// closer to a Gaussian in u than in x, and a proposal in u never lands outside the support. The
// density in u carries the Jacobian: log pi_u(u) = log pi_x(x(u)) + sum_j log dx_j/du_j.
#include <Eigen/Dense>

#include "bayes/target.hpp"

namespace terracal::bayes {

class BoxTransform {
 public:
  // Throws std::invalid_argument unless lower < upper, both finite, in every coordinate.
  BoxTransform(Eigen::VectorXd lower, Eigen::VectorXd upper);
  Eigen::VectorXd to_x(const Eigen::VectorXd& u) const;
  // Points on (or beyond) a bound map to u of the point 1e-9 of the width inside it.
  Eigen::VectorXd to_u(const Eigen::VectorXd& x) const;
  Eigen::VectorXd dx_du(const Eigen::VectorXd& u) const;  // the diagonal Jacobian
  double log_jacobian(const Eigen::VectorXd& u) const;
  // A covariance of x near x(u) carried to u (first order): D^-1 C D^-1, D = diag(dx/du).
  Eigen::MatrixXd covariance_to_u(const Eigen::VectorXd& u, const Eigen::MatrixXd& cx) const;

 private:
  Eigen::VectorXd lower_, width_;
};

// The target in u. Its log densities (single, batch and marginal) add the log Jacobian; its Gibbs
// step draws the nuisance given x(u). `t` and `box` must outlive the result.
Target in_unbounded_coordinates(const Target& t, const BoxTransform& box);

}  // namespace terracal::bayes
