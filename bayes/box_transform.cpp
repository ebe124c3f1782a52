#include "bayes/box_transform.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace terracal::bayes {

BoxTransform::BoxTransform(Eigen::VectorXd lower, Eigen::VectorXd upper) : lower_(std::move(lower)) {
  if (upper.size() != lower_.size()) throw std::invalid_argument("BoxTransform: bounds of different sizes");
  width_ = upper - lower_;
  for (Eigen::Index j = 0; j < width_.size(); ++j)
    if (!(std::isfinite(lower_[j]) && std::isfinite(upper[j]) && width_[j] > 0))
      throw std::invalid_argument("BoxTransform: every coordinate needs finite bounds, lower < upper");
}

Eigen::VectorXd BoxTransform::to_x(const Eigen::VectorXd& u) const {
  Eigen::VectorXd x(u.size());
  for (Eigen::Index j = 0; j < u.size(); ++j) x[j] = lower_[j] + width_[j] / (1.0 + std::exp(-u[j]));
  return x;
}

Eigen::VectorXd BoxTransform::to_u(const Eigen::VectorXd& x) const {
  Eigen::VectorXd u(x.size());
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    const double s = std::clamp((x[j] - lower_[j]) / width_[j], 1e-9, 1 - 1e-9);
    u[j] = std::log(s / (1 - s));
  }
  return u;
}

Eigen::VectorXd BoxTransform::dx_du(const Eigen::VectorXd& u) const {
  Eigen::VectorXd d(u.size());
  for (Eigen::Index j = 0; j < u.size(); ++j) {
    const double s = 1.0 / (1.0 + std::exp(-u[j]));
    d[j] = width_[j] * s * (1 - s);
  }
  return d;
}

double BoxTransform::log_jacobian(const Eigen::VectorXd& u) const {
  double l = 0;
  // log(w s (1 - s)) = log w - |u| - 2 log(1 + exp(-|u|)): no overflow for large |u|.
  for (Eigen::Index j = 0; j < u.size(); ++j)
    l += std::log(width_[j]) - std::fabs(u[j]) - 2.0 * std::log1p(std::exp(-std::fabs(u[j])));
  return l;
}

Eigen::MatrixXd BoxTransform::covariance_to_u(const Eigen::VectorXd& u, const Eigen::MatrixXd& cx) const {
  const Eigen::VectorXd inv = dx_du(u).cwiseInverse();
  return inv.asDiagonal() * cx * inv.asDiagonal();
}

Target in_unbounded_coordinates(const Target& t, const BoxTransform& box) {
  Target w;
  w.dim = t.dim;
  w.nuisance_dim = t.nuisance_dim;
  w.log_density = [&t, &box](const Eigen::VectorXd& u, const Eigen::VectorXd& nuisance) {
    return t.log_density(box.to_x(u), nuisance) + box.log_jacobian(u);
  };
  if (t.gibbs)
    w.gibbs = [&t, &box](const Eigen::VectorXd& u, Eigen::VectorXd& nuisance, Rng& rng) {
      t.gibbs(box.to_x(u), nuisance, rng);
    };
  const auto xs_of = [&box](const std::vector<Eigen::VectorXd>& us) {
    std::vector<Eigen::VectorXd> xs;
    for (const auto& u : us) xs.push_back(box.to_x(u));
    return xs;
  };
  if (t.log_density_batch)
    w.log_density_batch = [&t, &box, xs_of](const std::vector<Eigen::VectorXd>& us,
                                            const std::vector<Eigen::VectorXd>& nuisances, std::vector<double>& out) {
      t.log_density_batch(xs_of(us), nuisances, out);
      for (std::size_t i = 0; i < us.size() && i < out.size(); ++i) out[i] += box.log_jacobian(us[i]);
    };
  if (t.log_marginal_batch)
    w.log_marginal_batch = [&t, &box, xs_of](const std::vector<Eigen::VectorXd>& us, std::vector<double>& out) {
      t.log_marginal_batch(xs_of(us), out);
      for (std::size_t i = 0; i < us.size() && i < out.size(); ++i) out[i] += box.log_jacobian(us[i]);
    };
  return w;
}

}  // namespace terracal::bayes
