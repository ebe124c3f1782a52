#pragma once
// The Newton matrix of the GGL residual (mb_integrator.hpp), dr/dy + cj dr/dy', as a sparse matrix
// whose pattern is the same at every evaluation (a sparse direct solver factors it again with the
// pattern it analysed once).
//
// Unknowns y = [q | u | lambda | mu (one per position row) | mu_n (one per moving body)]; residual rows
// [q' - H (u + Phi_v^T mu) - q mu_n | M u' - f + Phi_v^T lambda | Phi | (|q|^2 - 1) / 2 | Phi_v u].
// Exact blocks: the mass, the kinematic map H and its derivative, Phi_v, Phi_q and the quaternion
// norms. Differenced: the applied forces against q and u (one evaluation of the system's forces per
// group of bodies and shafts that share no force element's row, per coordinate), and the
// q-derivatives of Phi_v^T lambda and Phi_v u (joint by joint, each joint alone). Left out: how
// Phi_v^T mu changes with q (mu vanishes on the solution, so Newton's convergence does not feel it).
#include <Eigen/Sparse>
#include <vector>

#include "highfi/multibody/mb_system.hpp"

namespace terracal::mb {

class GglJacobian {
 public:
  // The system's layout and its force elements' coupling are read now; call again after either changes.
  explicit GglJacobian(MbSystem& system);
  // The matrix at time t and unknowns y for the integrator's coefficient cj (dy'/dy). Leaves the
  // system's bodies and shafts in the state y.
  const Eigen::SparseMatrix<double>& evaluate(double t, const double* y, double cj);
  Eigen::Index size() const { return size_; }
  Eigen::Index nonzeros() const { return matrix_.nonZeros(); }
  // The groups of bodies and shafts whose applied forces are differenced together.
  int colors() const { return int(color_nodes_.size()); }

 private:
  struct Block {  // the constraint rows of one joint or one shaft coupling, and its moving bodies
    int row0 = 0, rows = 0;
    int joint = -1, shaft_body = -1;  // which one (the other is -1); a shaft linkage has neither
    std::vector<int> slots;           // moving slots of its bodies
  };
  void build_blocks();
  void build_coloring();
  void add(int r, int c, double v) { triplets_.emplace_back(r, c, v); }
  void kinematic_rows(const double* y, const Eigen::VectorXd& corrected, double cj);
  void mass_and_multiplier_columns(double cj);
  void constraint_rows(const double* y);
  void applied_force_columns(double t, const double* y);
  void joint_second_derivatives(const double* y);
  void differenced_joint_block(const Block& b, int slot, const double* y);

  MbSystem& s_;
  int nb_ = 0, ns_ = 0, nq_ = 0, nu_ = 0, m_ = 0, mh_ = 0;
  Eigen::Index size_ = 0;
  std::vector<Block> blocks_;
  std::vector<std::vector<int>> neighbours_;   // per node (moving slot, then shaft): nodes whose forces it moves
  std::vector<std::vector<int>> color_nodes_;  // per colour: its nodes
  Eigen::VectorXd phi_, f0_;
  Eigen::MatrixXd jac_;
  std::vector<Eigen::Triplet<double>> triplets_;
  Eigen::SparseMatrix<double> matrix_;
};

}  // namespace terracal::mb
