#pragma once
// Mean and covariance of all states so far, updated one state at a time (Welford), for the
// adaptive Metropolis proposal: O(dim^2) per iteration and no stored history.
#include <stdexcept>
#include <utility>

#include <Eigen/Dense>

namespace terracal::bayes {

class RunningCovariance {
 public:
  explicit RunningCovariance(Eigen::Index dim)
      : mean_(Eigen::VectorXd::Zero(dim)), scatter_(Eigen::MatrixXd::Zero(dim, dim)) {}

  void add(const Eigen::VectorXd& x) {
    ++count_;
    const Eigen::VectorXd delta = x - mean_;
    mean_ += delta / double(count_);
    // (n-1)/n * delta delta^T keeps the scatter matrix exactly symmetric.
    scatter_.noalias() += (double(count_ - 1) / double(count_)) * (delta * delta.transpose());
  }

  long count() const { return count_; }
  const Eigen::VectorXd& mean() const { return mean_; }
  const Eigen::MatrixXd& scatter() const { return scatter_; }  // sum of (x - mean)(x - mean)^T
  Eigen::MatrixXd covariance() const {
    if (count_ < 2) throw std::logic_error("RunningCovariance: fewer than 2 states");
    return scatter_ / double(count_ - 1);
  }

  // Restores a saved state (checkpoints).
  void restore(long count, Eigen::VectorXd mean, Eigen::MatrixXd scatter) {
    count_ = count;
    mean_ = std::move(mean);
    scatter_ = std::move(scatter);
  }

 private:
  long count_ = 0;
  Eigen::VectorXd mean_;
  Eigen::MatrixXd scatter_;
};

}  // namespace terracal::bayes
