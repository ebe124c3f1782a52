#include "bayes/model_point_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include <ceres/ceres.h>
#include <fmt/format.h>

#include "bayes/ceres_solve.hpp"
#include "core/errors.hpp"
#include "core/rng.hpp"

namespace terracal::bayes {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The posterior with the noise variances at their conditional optimum SSE_c/N_c (up to a constant),
// negated: lower is better; +inf for a failed run or a point outside the support.
double profile_objective(const ModelProblem& pb, const Eigen::VectorXd& x, const Eigen::VectorXd& sse) {
  const double lp = pb.log_prior(x);
  if (!std::isfinite(lp) || !sse.allFinite()) return kInf;
  double f = -lp;
  for (int c = 0; c < pb.num_channels(); ++c) {
    const double n = static_cast<double>(pb.channel(c).size());
    f += 0.5 * n * std::log(std::max(sse[c] / n, 1e-300));
  }
  return f;
}

// The start (each parameter's `initial`), then uniform draws inside the bounds, in batches, ranked
// by the profile objective. One start: the best of them all. More: the initial point (a vehicle's or
// soil's own values are the likeliest basin) and the starts - 1 best draws.
std::vector<Eigen::VectorXd> global_search(const ModelProblem& pb, const ModelPointOptions& o, int& evaluations) {
  Rng rng = Rng::for_stream(o.seed, 7);
  Eigen::VectorXd initial(pb.dim());
  for (int j = 0; j < pb.dim(); ++j) initial[j] = pb.parameter(j).initial;
  const double initial_f = profile_objective(pb, initial, pb.sse({initial})[0]);
  evaluations = 1;
  std::vector<std::pair<double, Eigen::VectorXd>> ranked;  // (objective, draw), the best `starts`, best first
  for (int done = 0; done < o.global_points;) {
    const int n = std::min(o.batch, o.global_points - done);
    std::vector<Eigen::VectorXd> xs(n, Eigen::VectorXd(pb.dim()));
    for (auto& x : xs)
      for (int j = 0; j < pb.dim(); ++j) {
        const Prior& pr = pb.parameter(j).prior;
        x[j] = pr.lower + (pr.upper - pr.lower) * rng.uniform();
      }
    const auto s = pb.sse(xs);
    for (int i = 0; i < n; ++i) {
      const double f = profile_objective(pb, xs[i], s[i]);
      if (!std::isfinite(f)) continue;
      const auto at = std::find_if(ranked.begin(), ranked.end(), [&](const auto& r) { return f < r.first; });
      if (at - ranked.begin() < o.starts) ranked.insert(at, {f, xs[i]});
      if (static_cast<int>(ranked.size()) > o.starts) ranked.pop_back();
    }
    done += n;
    evaluations += n;
  }
  std::vector<Eigen::VectorXd> out;
  if (std::isfinite(initial_f) && (o.starts > 1 || ranked.empty() || initial_f <= ranked.front().first))
    out.push_back(initial);
  for (auto& r : ranked)
    if (static_cast<int>(out.size()) < o.starts) out.push_back(std::move(r.second));
  if (out.empty())
    throw RunError(
        fmt::format("calibration: none of the {} points of the global search ran; check the references "
                    "and the priors",
                    evaluations));
  return out;
}

// Weighted residuals (f - y)/s_c of every row, their Jacobian by central differences (one-sided at a
// bound), the forward model run as one batch per evaluation. Works in scaled coordinates u = x/scale.
class BatchResiduals : public ceres::CostFunction {
 public:
  BatchResiduals(const ModelProblem& pb, const Eigen::VectorXd& scale, const Eigen::VectorXd& noise_sd, double step)
      : pb_(pb), scale_(scale), sd_(noise_sd), step_(step) {
    mutable_parameter_block_sizes()->push_back(pb.dim());
    set_num_residuals(static_cast<int>(pb.rows()));
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const int d = pb_.dim();
    Eigen::VectorXd x(d);
    for (int j = 0; j < d; ++j) x[j] = parameters[0][j] * scale_[j];
    std::vector<Eigen::VectorXd> xs{x};
    std::vector<double> lo(d), hi(d);
    if (jacobians && jacobians[0]) {
      for (int j = 0; j < d; ++j) {
        const Prior& pr = pb_.parameter(j).prior;
        const double h = step_ * scale_[j];
        lo[j] = std::max(x[j] - h, pr.lower);
        hi[j] = std::min(x[j] + h, pr.upper);
        Eigen::VectorXd a = x, b = x;
        a[j] = lo[j];
        b[j] = hi[j];
        xs.push_back(a);
        xs.push_back(b);
      }
    }
    const auto f = pb_.predict(xs);
    for (const auto& row : f)
      if (row.empty()) return false;  // a failed run: Ceres rejects the step
    weighted(f[0], residuals);
    if (!(jacobians && jacobians[0])) return true;
    std::vector<double> ra(pb_.rows()), rb(pb_.rows());
    for (int j = 0; j < d; ++j) {
      weighted(f[1 + 2 * j], ra.data());
      weighted(f[2 + 2 * j], rb.data());
      const double du = (hi[j] - lo[j]) / scale_[j];
      for (std::size_t i = 0; i < pb_.rows(); ++i) jacobians[0][i * d + j] = du > 0 ? (rb[i] - ra[i]) / du : 0.0;
    }
    return true;
  }

 private:
  void weighted(const std::vector<double>& f, double* r) const {
    std::size_t k = 0;
    for (int c = 0; c < pb_.num_channels(); ++c)
      for (std::size_t i = 0; i < pb_.channel(c).size(); ++i, ++k) r[k] = (f[k] - pb_.channel(c).y[i]) / sd_[c];
  }
  const ModelProblem& pb_;
  Eigen::VectorXd scale_, sd_;
  double step_;
};

Eigen::VectorXd scales(const ModelProblem& pb, const Eigen::VectorXd& x) {
  Eigen::VectorXd s(pb.dim());
  for (int j = 0; j < pb.dim(); ++j) {
    const Prior& pr = pb.parameter(j).prior;
    s[j] = std::max({std::abs(x[j]), 1e-3 * (pr.upper - pr.lower), 1e-12});
  }
  return s;
}

void update_noise(const ModelProblem& pb, PointEstimate& est) {
  const Eigen::VectorXd s = pb.sse({est.x})[0];
  est.noise_var.resize(pb.num_channels());
  est.weighted_rss = 0;
  for (int c = 0; c < pb.num_channels(); ++c) {
    est.noise_var[c] = std::max(s[c] / static_cast<double>(pb.channel(c).size()), 1e-24);
    est.weighted_rss += s[c] / est.noise_var[c];
  }
}

// The residuals in unbounded coordinates u_j, x_j = lower + (upper - lower) / (1 + exp(-u_j)): Ceres
// solves without bounds. (With bounds its projected steps evaluate the Jacobian at every trial point,
// 2 dim runs each: ten times the runs of this form on the HMMWV's 10 parameters.)
class LogitResiduals : public ceres::CostFunction {
 public:
  LogitResiduals(const ModelProblem& pb, const BatchResiduals& inner, const Eigen::VectorXd& scale)
      : pb_(pb), inner_(inner), scale_(scale) {
    mutable_parameter_block_sizes()->push_back(pb.dim());
    set_num_residuals(static_cast<int>(pb.rows()));
  }
  Eigen::VectorXd x_of(const double* u) const {
    Eigen::VectorXd x(pb_.dim());
    for (int j = 0; j < pb_.dim(); ++j) {
      const Prior& pr = pb_.parameter(j).prior;
      x[j] = pr.lower + (pr.upper - pr.lower) / (1.0 + std::exp(-u[j]));
    }
    return x;
  }
  Eigen::VectorXd u_of(const Eigen::VectorXd& x) const {
    Eigen::VectorXd u(pb_.dim());
    for (int j = 0; j < pb_.dim(); ++j) {
      const Prior& pr = pb_.parameter(j).prior;
      const double s = std::clamp((x[j] - pr.lower) / (pr.upper - pr.lower), 1e-6, 1 - 1e-6);
      u[j] = std::log(s / (1 - s));
    }
    return u;
  }
  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const int d = pb_.dim();
    const Eigen::VectorXd v = x_of(parameters[0]).cwiseQuotient(scale_);
    const double* p[] = {v.data()};
    if (!(jacobians && jacobians[0])) return inner_.Evaluate(p, residuals, nullptr);
    if (!inner_.Evaluate(p, residuals, jacobians)) return false;
    for (int j = 0; j < d; ++j) {  // d(x/scale)/du = (upper - lower) s (1 - s) / scale
      const Prior& pr = pb_.parameter(j).prior;
      const double s = 1.0 / (1.0 + std::exp(-parameters[0][j]));
      const double f = (pr.upper - pr.lower) * s * (1 - s) / scale_[j];
      for (std::size_t i = 0; i < pb_.rows(); ++i) jacobians[0][i * d + j] *= f;
    }
    return true;
  }

 private:
  const ModelProblem& pb_;
  const BatchResiduals& inner_;
  Eigen::VectorXd scale_;
};

// One least-squares solve from est.x at the current noise scales, inside the prior bounds.
void polish(const ModelProblem& pb, const ModelPointOptions& o, PointEstimate& est) {
  const Eigen::VectorXd scale = scales(pb, est.x);
  const BatchResiduals inner(pb, scale, est.noise_var.cwiseSqrt(), o.relative_step);
  auto* cost = new LogitResiduals(pb, inner, scale);
  Eigen::VectorXd u = cost->u_of(est.x);
  ceres::Problem problem;
  problem.AddResidualBlock(cost, nullptr, u.data());
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = o.max_iterations;
  options.function_tolerance = 1e-10;
  options.parameter_tolerance = 1e-10;
  options.num_threads = 1;
  ceres::Solver::Summary summary;
  solve_quietly(options, &problem, &summary);
  est.ceres_report = summary.BriefReport();
  const Eigen::VectorXd candidate = cost->x_of(u.data());
  if (profile_objective(pb, candidate, pb.sse({candidate})[0]) <= profile_objective(pb, est.x, pb.sse({est.x})[0]))
    est.x = candidate;
}

}  // namespace

// (J^T J)^-1 of the weighted residuals at est.x, each channel's residuals divided by its noise
// scale sqrt(noise_var tau) (tau its correlation time: each row then carries 1/tau of a row's
// information, as in the likelihood). In scaled coordinates (unit: the parameter's size)
// a direction's variance is kept within [1e-14, 1]: data from a simulation can pin a parameter far
// more tightly than bevameter curves pin a soil (a floor of 1e-6 would make proposals 1000 times too
// wide), and a direction the data leave open (information below 1e-12 of the largest) is counted
// and given the prior's scale.
void laplace_covariance(const ModelProblem& pb, const ModelPointOptions& o, PointEstimate& est) {
  const int d = pb.dim();
  const Eigen::VectorXd scale = scales(pb, est.x);
  const Eigen::VectorXd u = est.x.cwiseQuotient(scale);
  Eigen::VectorXd sd(pb.num_channels());
  for (int c = 0; c < pb.num_channels(); ++c) sd[c] = std::sqrt(est.noise_var[c] * pb.correlation_time(c));
  BatchResiduals res(pb, scale, sd, o.relative_step);
  Eigen::VectorXd r(pb.rows());
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> J(pb.rows(), d);
  const double* params[] = {u.data()};
  double* jac[] = {J.data()};
  constexpr double kMinScaledVariance = 1e-14;
  Eigen::MatrixXd cov_u = Eigen::MatrixXd::Identity(d, d) * 1e-6;
  bool computed = res.Evaluate(params, r.data(), jac) && J.allFinite();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(computed ? Eigen::MatrixXd(J.transpose() * J)
                                                              : Eigen::MatrixXd::Identity(d, d));
  Eigen::VectorXd lambda = eig.eigenvalues();  // of the information matrix
  const double lambda_max = std::max(lambda.maxCoeff(), 1e-300);
  int unconstrained = 0;
  Eigen::VectorXd var(d);
  for (int a = 0; a < d; ++a) {
    const bool open = lambda[a] < 1e-12 * lambda_max;
    unconstrained += open;
    var[a] = computed && !open ? std::clamp(1.0 / lambda[a], kMinScaledVariance, 1.0) : 1.0;
  }
  if (computed) cov_u = eig.eigenvectors() * var.asDiagonal() * eig.eigenvectors().transpose();
  est.covariance_ok = computed && unconstrained == 0;
  est.unconstrained_directions = computed ? unconstrained : d;
  est.covariance = scale.asDiagonal() * cov_u * scale.asDiagonal();
}

namespace {

// One least-squares round at est's noise scales, then the scales at its result; true once they have
// settled (moved by < 1e-9 relative): the point is then the least-squares point of its own noise.
bool polish_round(const ModelProblem& pb, const ModelPointOptions& o, PointEstimate& est) {
  const Eigen::VectorXd before = est.noise_var;
  polish(pb, o, est);
  update_noise(pb, est);
  return ((est.noise_var - before).array().abs() <= 1e-9 * before.array()).all();
}

}  // namespace

// Every start gets one round, and the best by the profile objective goes on. Where weights follow the
// noise, a start in a poor basin can settle there: a channel it fits badly gets a large noise
// variance, so little weight, and the fit no longer pulls on it. The profile objective does not move
// with the weights. (One round each, not a full solve each: the rounds after the first move the
// point little, and on the HMMWV the starts' first rounds already differ by 10^4 in the objective.)
PointEstimate estimate_model_point(const ModelProblem& pb, const ModelPointOptions& o) {
  if (o.starts < 1) throw std::invalid_argument("estimate_model_point: starts must be at least 1");
  int evaluations = 0;
  const std::vector<Eigen::VectorXd> starts = global_search(pb, o, evaluations);
  PointEstimate best;
  bool settled = o.polish_rounds <= 0;
  std::vector<double> objectives;
  for (std::size_t k = 0; k < starts.size(); ++k) {
    PointEstimate est;
    est.x = starts[k];
    update_noise(pb, est);
    const bool done = o.polish_rounds <= 0 || polish_round(pb, o, est);
    objectives.push_back(profile_objective(pb, est.x, pb.sse({est.x})[0]));
    if (k == 0 || objectives[k] < objectives[best.start]) {
      best = std::move(est);
      best.start = static_cast<int>(k);
      settled = done;
    }
  }
  for (int round = 1; round < o.polish_rounds && !settled; ++round) settled = polish_round(pb, o, best);
  best.global_evaluations = evaluations;
  best.start_objectives = std::move(objectives);
  laplace_covariance(pb, o, best);
  return best;
}

}  // namespace terracal::bayes
