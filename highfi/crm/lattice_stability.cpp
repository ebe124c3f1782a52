#include "highfi/crm/lattice_stability.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Dense>

namespace terracal {

namespace {
struct LatticeTerm {
  Eigen::Vector3d l;     // lattice vector in units of d0
  Eigen::Matrix3d hess;  // V Hess W(l), units of d0 (V = d0^3, W ~ 1/d0^3, two derivatives)
  Eigen::Vector3d grad;  // V grad W(l)
};

// Hess W = F I + r F'(r) n n^T with F = W'/r the kernel's gradient factor; F' by central differences
// (double precision, a step of 1e-6 support: relative error ~1e-10, far below what matters here).
std::vector<LatticeTerm> lattice_terms(KernelType kernel, double h_over_d0) {
  const SphKernel<double> w = SphKernel<double>::make(kernel, h_over_d0);
  const int reach = int(std::ceil(2 * h_over_d0));
  std::vector<LatticeTerm> terms;
  for (int i = -reach; i <= reach; ++i)
    for (int j = -reach; j <= reach; ++j)
      for (int k = -reach; k <= reach; ++k) {
        if (i == 0 && j == 0 && k == 0) continue;
        const Eigen::Vector3d l(i, j, k);
        const double r = l.norm();
        if (r >= 2 * h_over_d0) continue;
        const double step = 1e-6 * h_over_d0;
        const double f = w.grad_factor(r);
        const double fp = (w.grad_factor(r + step) - w.grad_factor(r - step)) / (2 * step);
        LatticeTerm t;
        t.l = l;
        t.hess = f * Eigen::Matrix3d::Identity() + (fp / r) * l * l.transpose();
        t.grad = f * l;
        terms.push_back(t);
      }
  return terms;
}
// rho omega^2 d0^2 for wave vector k (units 1/d0) and the geometric stiffness D(k).
Eigen::Matrix3d dynamic_matrix(const std::vector<LatticeTerm>& terms, const Eigen::Vector3d& k,
                               const Eigen::Matrix3d& sigma, double lambda, double mu,
                               Eigen::Matrix3d* geometric = nullptr) {
  Eigen::Matrix3d D = Eigen::Matrix3d::Zero();
  Eigen::Vector3d G = Eigen::Vector3d::Zero();
  for (const LatticeTerm& t : terms) {
    const double kl = k.dot(t.l);
    D += (1 - std::cos(kl)) * t.hess;
    G += std::sin(kl) * t.grad;
  }
  if (geometric) *geometric = D;
  return -2 * sigma * D + (lambda + mu) * G * G.transpose() + mu * G.squaredNorm() * Eigen::Matrix3d::Identity();
}

constexpr double kPi = 3.14159265358979323846;
}  // namespace

std::array<std::array<double, 3>, 3> lattice_mode_omega2(KernelType kernel, double h_over_d0, double d0, double rho,
                                                         double lambda, double mu, const std::array<double, 3>& stress,
                                                         const std::array<double, 3>& k_over_pi) {
  const Eigen::Matrix3d sigma = Eigen::Vector3d(stress[0], stress[1], stress[2]).asDiagonal();
  const Eigen::Matrix3d M =
      dynamic_matrix(lattice_terms(kernel, h_over_d0), kPi * Eigen::Vector3d(k_over_pi[0], k_over_pi[1], k_over_pi[2]),
                     sigma, lambda, mu);
  std::array<std::array<double, 3>, 3> out{};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) out[a][b] = M(a, b) / (rho * d0 * d0);
  return out;
}

LatticeStability lattice_stability(KernelType kernel, double h_over_d0, double d0, double rho, double lambda, double mu,
                                   const std::array<double, 3>& stress, int samples) {
  const std::vector<LatticeTerm> terms = lattice_terms(kernel, h_over_d0);
  const Eigen::Matrix3d sigma = Eigen::Vector3d(stress[0], stress[1], stress[2]).asDiagonal();
  LatticeStability out;
  double worst = 0;  // most negative eigenvalue of rho omega^2 d0^2
  for (int a = 0; a <= samples; ++a)
    for (int b = 0; b <= samples; ++b)
      for (int c = 0; c <= samples; ++c) {
        if (a == 0 && b == 0 && c == 0) continue;
        const Eigen::Vector3d k = (kPi / samples) * Eigen::Vector3d(a, b, c);
        Eigen::Matrix3d D;
        const Eigen::Matrix3d M = dynamic_matrix(terms, k, sigma, lambda, mu, &D);
        out.min_geometric =
            std::min(out.min_geometric, Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(D).eigenvalues()(0));
        const Eigen::Vector3cd ev = Eigen::EigenSolver<Eigen::Matrix3d>(M, false).eigenvalues();
        for (int q = 0; q < 3; ++q)
          if (ev(q).real() < worst) {
            worst = ev(q).real();
            out.wave = {double(a) / samples, double(b) / samples, double(c) / samples};
          }
      }
  out.growth_rate = worst < 0 ? std::sqrt(-worst / rho) / d0 : 0;
  return out;
}

}  // namespace terracal
