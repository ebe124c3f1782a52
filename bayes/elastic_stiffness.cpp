#include "bayes/elastic_stiffness.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>
#include <gsl/gsl_cdf.h>
#include <Eigen/Dense>

#include "bayes/forward_models.hpp"

namespace terracal::bayes {
namespace {

const char* phase_name(PlatePhase p) { return p == PlatePhase::kUnload ? "unload" : "reload"; }

// In SCM a reloaded node follows sigma = Ke (z - z_p) until it meets the Bekker curve again at its
// previous maximum sinkage, so reload rows at or below that maximum are elastic with the same Ke.
// They get their own intercept rather than sharing the preceding unload branch's: real and CRM
// soils show some hysteresis (the reload line is offset from the unload line), and an own
// intercept keeps the slope honest there at the cost of one degree of freedom.
bool is_elastic(const PlatePoint& p) {
  return p.phase == PlatePhase::kUnload || (p.phase == PlatePhase::kReload && !p.fitted);
}

struct Branch {
  ElasticBranch info;
  std::vector<const PlatePoint*> rows;  // force > 0 only
};

// Maximal runs of consecutive elastic rows of one plate and one phase, in file order.
std::vector<Branch> find_branches(const PlateData& plate, int& lift_off_rows) {
  std::vector<Branch> out;
  const PlatePoint* prev = nullptr;
  for (const auto& p : plate.points) {
    if (is_elastic(p)) {
      if (!prev || !is_elastic(*prev) || prev->radius != p.radius || prev->phase != p.phase)
        out.push_back({ElasticBranch{p.radius, p.phase, p.line, 0, 0.0}, {}});
      // Below its plastic sinkage the plate has left the soil: F = 0 there, not Ke (z - z_p) < 0.
      if (p.force > 0)
        out.back().rows.push_back(&p);
      else
        ++lift_off_rows;
    }
    prev = &p;
  }
  return out;
}

// The branches with at least 2 rows of force > 0 (a slope needs two); the others are noted in `fit`.
std::vector<Branch> usable_branches(std::vector<Branch> found, const PlateData& plate, ElasticFit& fit) {
  std::vector<Branch> branches;
  for (auto& b : found) {
    if (b.rows.size() >= 2) {
      branches.push_back(std::move(b));
      continue;
    }
    fit.notes.push_back(
        fmt::format("{}:{}: the {} branch of the plate r = {:g} m has {} row(s) with force > 0; a slope needs "
                    "at least 2: branch ignored for the elastic stiffness",
                    plate.path, b.info.first_line, phase_name(b.info.phase), b.info.radius, b.rows.size()));
  }
  return branches;
}

// The least-squares problem A [Ke, c_1 ... c_k] = y of the branches: one slope, one intercept per branch.
void whitened_design(const PlateData& plate, const std::vector<Branch>& branches, bool relative_noise,
                     Eigen::MatrixXd& A, Eigen::VectorXd& y) {
  std::map<double, double> plate_max;  // largest force per plate: the floor of the relative weights
  for (const auto& p : plate.points) plate_max[p.radius] = std::max(plate_max[p.radius], p.force);
  int n = 0;
  for (const auto& b : branches) n += static_cast<int>(b.rows.size());
  const int cols = 1 + static_cast<int>(branches.size());
  // Whitened design: row i divided by its noise weight w_i. The slope column is measured from the
  // branch's first sinkage, not from z = 0: within a branch z moves by millimetres at a depth of
  // centimetres, and the offset keeps that column from being nearly parallel to the intercept's.
  A = Eigen::MatrixXd::Zero(n, cols);
  y.resize(n);
  int i = 0;
  for (std::size_t k = 0; k < branches.size(); ++k) {
    const double r = branches[k].info.radius, z_ref = branches[k].rows.front()->sinkage;
    for (const PlatePoint* p : branches[k].rows) {
      const double w = relative_noise ? std::max(p->force, 0.01 * plate_max[r]) : 1.0;
      A(i, 0) = kPi * r * r * (p->sinkage - z_ref) / w;
      A(i, 1 + static_cast<int>(k)) = 1.0 / w;
      y[i] = p->force / w;
      ++i;
    }
  }
}

}  // namespace

double ElasticFit::quantile(double p) const { return fitted ? ke + sd * gsl_cdf_ugaussian_Pinv(p) : ke; }

ElasticFit fit_elastic_stiffness(const PlateData& plate, bool relative_noise) {
  ElasticFit fit;
  const std::string keep_default =
      fmt::format("Elastic stiffness not fitted: Chrono's default {:g} Pa/m is used", kDefaultElasticStiffness);
  std::vector<Branch> found = find_branches(plate, fit.lift_off_rows);
  if (found.empty()) {
    fit.notes.push_back(fmt::format("{}: no unload rows (phase = unload); {}", plate.path, keep_default));
    return fit;
  }
  const std::vector<Branch> branches = usable_branches(std::move(found), plate, fit);
  if (branches.empty()) {
    fit.notes.push_back(
        fmt::format("{}: no unload or reload branch with 2 or more rows of force > 0; {}", plate.path, keep_default));
    return fit;
  }

  Eigen::MatrixXd A;
  Eigen::VectorXd y;
  whitened_design(plate, branches, relative_noise, A, y);
  const int n = static_cast<int>(A.rows()), cols = static_cast<int>(A.cols());
  // Unit column norms first: Ke multiplies ~1e-3 m^3 where an intercept multiplies 1, and the
  // rank decision of the pivoting QR needs comparable columns.
  const Eigen::VectorXd scale = A.colwise().norm().transpose().cwiseMax(1e-300);
  const Eigen::MatrixXd As = A * scale.cwiseInverse().asDiagonal();
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(As);
  if (qr.rank() < cols) {
    fit.notes.push_back(
        fmt::format("{}: the unload/reload rows do not determine a slope (each branch has a single sinkage); {}",
                    plate.path, keep_default));
    return fit;
  }
  const Eigen::VectorXd beta = qr.solve(y).cwiseQuotient(scale);
  const double ke = beta[0];
  fit.rows = n;
  fit.dof = n - cols;
  if (fit.dof < 1) {
    fit.notes.push_back(
        fmt::format("{}: {} unload/reload rows in {} branch(es) give Ke = {:.6g} Pa/m but leave no degree of "
                    "freedom for its standard error (add rows to a branch); {}",
                    plate.path, n, branches.size(), ke, keep_default));
    return fit;
  }
  // Var(beta) = s^2 (A^T A)^-1 with s^2 the weighted residual variance; from the QR factors,
  // (A^T A)^-1 = P R^-1 R^-T P^T in scaled columns.
  const double s2 = (y - A * beta).squaredNorm() / fit.dof;
  const Eigen::MatrixXd R = qr.matrixR().topLeftCorner(cols, cols).triangularView<Eigen::Upper>();
  const Eigen::MatrixXd Rinv = R.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(cols, cols));
  const Eigen::MatrixXd cov = qr.colsPermutation() * (Rinv * Rinv.transpose()) * qr.colsPermutation().transpose();
  const double sd = std::sqrt(s2 * cov(0, 0)) / scale[0];
  if (!(ke > 0) || !std::isfinite(sd)) {
    // Force rising as the plate rises means mislabelled phases or a sensor problem, not a soil.
    fit.notes.push_back(
        fmt::format("{}: the unload/reload branches give a slope Ke = {:.6g} +- {:.3g} Pa/m, which is not positive: "
                    "the force does not fall as the plate rises (check the phase labels); {}",
                    plate.path, ke, sd, keep_default));
    return fit;
  }
  fit.fitted = true;
  fit.ke = ke;
  fit.sd = sd;
  fit.noise_sd = std::sqrt(s2);
  for (std::size_t k = 0; k < branches.size(); ++k) {
    ElasticBranch info = branches[k].info;
    info.rows = static_cast<int>(branches[k].rows.size());
    const double z_ref = branches[k].rows.front()->sinkage;
    info.plastic_sinkage = z_ref - beta[1 + static_cast<int>(k)] / (kPi * info.radius * info.radius * ke);
    fit.branches.push_back(info);
  }
  return fit;
}

}  // namespace terracal::bayes
