#include "bayes/point_estimate.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>

#include <ceres/ceres.h>
#include <fmt/format.h>
#include <nlopt.hpp>

#include "bayes/ceres_solve.hpp"
#include "core/errors.hpp"

namespace terracal::bayes {
namespace {

constexpr double kHuge = 1e300;
// The random search over the wheel-only coordinates (with the annulus scaled): each evaluation is a
// steady-wheel sweep of milliseconds.
constexpr int kWheelSearchEvaluations = 600;

// The global search works in coordinates where the data are informative and scales are even:
// plate stiffness as log K(r) = log(Kc/r + Kphi) at the smallest and largest plate radius (what
// each plate measures, and positive by construction), log k, and c, phi, n as they are. With the
// annulus's law scaled (calibration_problem.hpp) the shear coordinates are the annulus's own
// (c / R, its friction angle, log k_annulus), which the bevameter curves alone pin, and log R and
// log k follow: the wheel's coordinates, with S.
class SearchSpace {
 public:
  explicit SearchSpace(const CalibrationProblem& pb) : pb_(pb) {
    const auto& pr = pb.priors();
    const auto is_free = [&](int i) { return !pr[i].fixed(); };
    r1_ = pb.plate_radii().front();
    r2_ = pb.plate_radii().back();
    kc_free_ = is_free(kKc);
    kphi_free_ = is_free(kKphi);
    scaled_ = pb.annulus_scaled();
    if (kc_free_ || kphi_free_) add(std::log(1.0), std::log(1e12));  // log K(r1)
    if (kc_free_ && kphi_free_) {
      if (r2_ > r1_)
        add(std::log(1.0), std::log(1e12));  // log K(r2)
      else
        add(pr[kKc].lower, pr[kKc].upper);  // one radius, Kc has a prior
    }
    add_free(kN, pr[kN].lower, pr[kN].upper);
    add_free(kCohesion, pr[kCohesion].lower,
             std::min(pr[kCohesion].upper, std::max(pr[kCohesion].lower + 1.0, 3.0 * max_shear_stress())));
    add_free(kFriction, pr[kFriction].lower, pr[kFriction].upper);
    const int annulus_k = scaled_ ? kAnnulusJanosi : kJanosi;
    add_free(annulus_k, std::log(pr[annulus_k].lower), std::log(pr[annulus_k].upper));
    if (scaled_) {
      add_free(kShearRatio, std::log(pr[kShearRatio].lower), std::log(pr[kShearRatio].upper), true);
      add_free(kJanosi, std::log(pr[kJanosi].lower), std::log(pr[kJanosi].upper), true);
    }
    add_free(kSlipSinkage, pr[kSlipSinkage].lower, pr[kSlipSinkage].upper, true);
  }

  int dim() const { return static_cast<int>(lo_.size()); }
  // The coordinates only the wheel curves see (S; with the annulus scaled also log R and log k).
  const std::vector<int>& wheel_coordinates() const { return wheel_; }

  ParamVector decode(const std::vector<double>& u) const {
    ParamVector p = pb_.fixed_values();
    std::size_t j = 0;
    if (kc_free_ || kphi_free_) {
      const double k1 = std::exp(u[j++]);
      if (kc_free_ && kphi_free_) {
        if (r2_ > r1_) {
          const double k2 = std::exp(u[j++]);
          p[kKc] = (k1 - k2) / (1.0 / r1_ - 1.0 / r2_);
        } else {
          p[kKc] = u[j++];
        }
        p[kKphi] = k1 - p[kKc] / r1_;
      } else if (kc_free_) {
        p[kKc] = (k1 - p[kKphi]) * r1_;
      } else {
        p[kKphi] = k1 - p[kKc] / r1_;
      }
    }
    const auto at = [&](int i) { return u[std::size_t(slot_[i])]; };
    if (slot_[kN] >= 0) p[kN] = at(kN);
    if (slot_[kCohesion] >= 0) p[kCohesion] = at(kCohesion);
    if (slot_[kFriction] >= 0) p[kFriction] = at(kFriction);
    if (slot_[kJanosi] >= 0) p[kJanosi] = std::exp(at(kJanosi));
    if (slot_[kSlipSinkage] >= 0) p[kSlipSinkage] = at(kSlipSinkage);
    if (scaled_) {
      if (slot_[kAnnulusJanosi] >= 0) p[kAnnulusJanosi] = std::exp(at(kAnnulusJanosi));
      if (slot_[kShearRatio] >= 0) p[kShearRatio] = std::exp(at(kShearRatio));
      // c and phi were searched as the annulus's: the set's strength is R times it.
      const double R = p[kShearRatio];
      if (slot_[kCohesion] >= 0) p[kCohesion] *= R;
      if (slot_[kFriction] >= 0) p[kFriction] = std::atan(R * std::tan(p[kFriction] * kPi / 180.0)) * 180.0 / kPi;
    }
    return p;
  }

  const std::vector<double>& lower() const { return lo_; }
  const std::vector<double>& upper() const { return hi_; }

 private:
  void add(double lo, double hi) {
    lo_.push_back(lo);
    hi_.push_back(hi);
  }
  // A coordinate for parameter i if it is free; `wheel`: one only the wheel curves see.
  void add_free(int i, double lo, double hi, bool wheel = false) {
    if (pb_.priors()[i].fixed()) return;
    slot_[i] = dim();
    if (wheel) wheel_.push_back(dim());
    add(lo, hi);
  }
  // The largest mean shear stress any shear row implies (torque over the developed-torque lever).
  double max_shear_stress() const {
    double m = 0;
    for (int t = 0; t < pb_.num_types(); ++t) {
      const auto& s = pb_.set(t);
      if (s.name != "shear") continue;
      for (std::size_t i = 0; i < s.size(); ++i)
        m = std::max(m, std::abs(s.y[i]) / (2.0 * kPi * (std::pow(s.r_out[i], 3) - std::pow(s.r_in[i], 3)) / 3.0));
    }
    return m;
  }

  const CalibrationProblem& pb_;
  double r1_ = 0, r2_ = 0;
  bool kc_free_ = false, kphi_free_ = false, scaled_ = false;
  std::vector<double> lo_, hi_;
  std::array<int, kNumParams> slot_ = filled(-1);  // coordinate of parameter i, -1 if fixed
  std::vector<int> wheel_;
  static std::array<int, kNumParams> filled(int v) {
    std::array<int, kNumParams> a;
    a.fill(v);
    return a;
  }
};

// NLopt's derivative-free objective: `data` points at a std::function of the coordinates.
double nlopt_objective(const std::vector<double>& u, std::vector<double>&, void* data) {
  return (*static_cast<std::function<double(const std::vector<double>&)>*>(data))(u);
}

// Negative log posterior with the noise variances profiled out: sum_t N_t/2 log SSE_t - log prior
// (without the wheel types when `wheel` is false).
double profile_objective(const CalibrationProblem& pb, const ParamVector& p, bool wheel = true) {
  const double lp = pb.log_prior(p);
  if (!std::isfinite(lp)) return kHuge;
  double f = -lp;
  for (int t = 0; t < pb.num_types(); ++t) {
    if (!wheel && pb.set(t).is_wheel()) continue;
    const double sse = pb.weighted_sse(t, p);
    if (!std::isfinite(sse)) return kHuge;
    f += 0.5 * pb.effective_rows(t) * std::log(std::max(sse, 1e-300));
  }
  return f;
}

// With wheel curves the search is staged: the steady wheel costs milliseconds where the bevameter
// models cost microseconds, so the random search explores on the bevameter curves alone, then the
// coordinates only the wheel sees are searched with the others held (a scan of S; with the annulus
// scaled, a random search over log R, log k and S), and BOBYQA converges on every curve.
void search_wheel_coordinates(const SearchSpace& space, const std::function<double(const std::vector<double>&)>& f,
                              std::vector<double>& u, int seed_evaluations) {
  const std::vector<int>& w = space.wheel_coordinates();
  if (w.empty()) return;
  if (w.size() == 1) {
    const int j = w.front();
    double best = kHuge, best_s = u[j];
    constexpr int kScan = 21;
    for (int k = 0; k < kScan; ++k) {
      u[j] = space.lower()[j] + (space.upper()[j] - space.lower()[j]) * k / (kScan - 1);
      const double v = f(u);
      if (v < best) best = v, best_s = u[j];
    }
    u[j] = best_s;
    return;
  }
  std::vector<double> v(w.size()), lo(w.size()), hi(w.size());
  for (std::size_t m = 0; m < w.size(); ++m) {
    lo[m] = space.lower()[w[m]], hi[m] = space.upper()[w[m]];
    v[m] = 0.5 * (lo[m] + hi[m]);
  }
  std::function<double(const std::vector<double>&)> g = [&](const std::vector<double>& x) {
    std::vector<double> full = u;
    for (std::size_t m = 0; m < w.size(); ++m) full[w[m]] = x[m];
    return f(full);
  };
  nlopt::opt crs(nlopt::GN_CRS2_LM, static_cast<unsigned>(w.size()));
  crs.set_lower_bounds(lo);
  crs.set_upper_bounds(hi);
  crs.set_min_objective(nlopt_objective, &g);
  crs.set_maxeval(seed_evaluations);
  crs.set_population(static_cast<unsigned>(10 * (w.size() + 1)));
  crs.set_xtol_rel(1e-6);
  double best = kHuge;
  try {
    crs.optimize(v, best);
  } catch (const std::exception&) { /* keep the best point found */
  }
  if (best < kHuge)
    for (std::size_t m = 0; m < w.size(); ++m) u[w[m]] = v[m];
}

ParamVector global_search(const CalibrationProblem& pb, const PointEstimateOptions& opt, int& evaluations) {
  SearchSpace space(pb);
  if (space.dim() == 0) return pb.fixed_values();
  bool wheel = !pb.has_wheel();  // the random search's objective (see search_wheel_coordinates)
  std::function<double(const std::vector<double>&)> f = [&](const std::vector<double>& u) {
    ++evaluations;
    return profile_objective(pb, space.decode(u), wheel);
  };
  nlopt::srand(opt.seed);
  std::vector<double> u(space.dim());
  for (int j = 0; j < space.dim(); ++j) u[j] = 0.5 * (space.lower()[j] + space.upper()[j]);
  double best = kHuge;
  // Controlled random search with local mutation explores the box; BOBYQA then converges locally.
  nlopt::opt crs(nlopt::GN_CRS2_LM, space.dim());
  crs.set_lower_bounds(space.lower());
  crs.set_upper_bounds(space.upper());
  crs.set_min_objective(nlopt_objective, &f);
  crs.set_maxeval(opt.global_evaluations);
  crs.set_population(static_cast<unsigned>(30 * (space.dim() + 1)));
  crs.set_xtol_rel(1e-8);
  try {
    crs.optimize(u, best);
  } catch (const std::exception&) { /* keep the best point found */
  }
  if (!wheel) {
    wheel = true;
    search_wheel_coordinates(space, f, u, kWheelSearchEvaluations);
    best = f(u);
  }
  nlopt::opt local(nlopt::LN_BOBYQA, space.dim());
  local.set_lower_bounds(space.lower());
  local.set_upper_bounds(space.upper());
  local.set_min_objective(nlopt_objective, &f);
  local.set_maxeval(5000);
  local.set_xtol_rel(1e-10);
  try {
    local.optimize(u, best);
  } catch (const std::exception&) {
  }
  if (best >= kHuge)
    throw RunError("global search: no parameter set inside the priors explains the data (every evaluation failed)");
  return space.decode(u);
}

// Ceres works on scaled parameters u = p / scale (scale ~ |p| at the start): the raw parameters
// span thirteen orders of magnitude (Kphi ~ 1e6 Pa/m^n, k ~ 1e-2 m), which would make the
// Jacobian so ill-conditioned that DENSE_SVD's rank cut drops real directions and the covariance
// comes out too small.
using Scale = std::array<double, kNumParams>;

template <typename T>
std::array<T, kNumParams> unscale(const T* u, const Scale& scale) {
  std::array<T, kNumParams> p;
  for (int i = 0; i < kNumParams; ++i) p[i] = u[i] * scale[i];
  return p;
}

// Weighted residuals (y - f) / (s_t w_i) of one test type, for Ceres' automatic differentiation.
struct TypeResiduals {
  const CalibrationProblem* pb;
  int t;
  double noise_sd;
  Scale scale;
  template <typename T>
  bool operator()(T const* const* u, T* residuals) const {
    const auto p = unscale(u[0], scale);
    const ObservationSet& s = pb->set(t);
    pb->predict_set(t, p.data(), residuals);
    for (std::size_t i = 0; i < s.size(); ++i) residuals[i] = (s.y[i] - residuals[i]) / (noise_sd * s.w[i]);
    return true;
  }
};

// The wheel types' residuals, all three from one steady-wheel evaluation: that model is double only
// (an adaptive quadrature), so Ceres differentiates it numerically. Its tolerance (1e-8) is far
// below the relative step of 1e-4, so the differences see the model, not its round-off.
struct WheelResiduals {
  const CalibrationProblem* pb;
  std::vector<int> types;
  std::vector<double> noise_sd;
  Scale scale;
  bool operator()(double const* const* u, double* residuals) const {
    ParamVector p;
    for (int i = 0; i < kNumParams; ++i) p[i] = u[0][i] * scale[i];
    const WheelPrediction& f = pb->predict_wheel(p);
    for (std::size_t k = 0; k < types.size(); ++k) {
      const ObservationSet& s = pb->set(types[k]);
      const std::vector<double>& fk = f.channel(s.kind);
      for (std::size_t i = 0; i < s.size(); ++i) {
        if (!std::isfinite(fk[i])) return false;
        *residuals++ = (s.y[i] - fk[i]) / (noise_sd[k] * s.w[i]);
      }
    }
    return true;
  }
};

// Gaussian priors enter the least-squares problem as one more residual (lognormal: on the log).
struct PriorResidual {
  int i;
  Prior prior;
  double scale;
  template <typename T>
  bool operator()(const T* u, T* r) const {
    using std::log;
    const T p = u[i] * scale;
    r[0] = prior.kind == Prior::Kind::kLogNormal ? (log(p) - prior.mean) / prior.sd : (p - prior.mean) / prior.sd;
    return true;
  }
};

// The covariance of the free parameters at the polished point, from the Jacobian of `problem` (whose
// parameter block is `u`, the parameters over `scale`), made positive definite.
void estimate_covariance(const CalibrationProblem& pb, ceres::Problem& problem,
                         const std::vector<ceres::ResidualBlockId>& data_blocks, const Scale& scale, double* u,
                         PointEstimate& est) {
  // Covariance of the free parameters: DENSE_SVD tolerates a rank-deficient Jacobian.
  ceres::Covariance::Options copt;
  copt.algorithm_type = ceres::DENSE_SVD;
  copt.null_space_rank = -1;
  copt.num_threads = 1;
  for (int i = 0; i < kNumParams; ++i) u[i] = est.map[i] / scale[i];
  ceres::Covariance covariance(copt);
  const int d = pb.dim();
  const std::vector<std::pair<const double*, const double*>> blocks = {{u, u}};
  Eigen::MatrixXd cov_u = Eigen::MatrixXd::Zero(d, d);  // in scaled coordinates
  bool computed = false;
  if (covariance.Compute(blocks, &problem)) {
    Eigen::Matrix<double, kNumParams, kNumParams, Eigen::RowMajor> full;
    covariance.GetCovarianceBlock(u, u, full.data());
    // Scaled by the residual variance of the data (the prior residuals are not noise).
    double n_total = 0;  // rows, each type's counted as N_t / tau_t
    ceres::Problem::EvaluateOptions data_only;
    data_only.residual_blocks = data_blocks;
    for (int t = 0; t < pb.num_types(); ++t) n_total += pb.effective_rows(t);
    double cost = 0;
    problem.Evaluate(data_only, &cost, nullptr, nullptr, nullptr);
    const double variance_factor = n_total > d ? 2.0 * cost / (n_total - d) : 1.0;
    for (int a = 0; a < d; ++a)
      for (int b = 0; b < d; ++b) cov_u(a, b) = variance_factor * full(pb.free_indices()[a], pb.free_indices()[b]);
    computed = cov_u.allFinite();
  }
  // DENSE_SVD leaves (near-)zero variance along directions the data do not constrain, and a
  // covariance that is not positive definite cannot serve as a proposal. In scaled coordinates
  // (unit ~ the parameter's size) give every direction at least a variance of (1e-3)^2 and tell
  // the user when that was needed because the data leave a combination of parameters open.
  constexpr double kMinScaledVariance = 1e-6;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(computed ? cov_u
                                                              : Eigen::MatrixXd::Identity(d, d) * kMinScaledVariance);
  Eigen::VectorXd lambda = eig.eigenvalues();
  const double lambda_max = std::max(lambda.maxCoeff(), kMinScaledVariance);
  int unconstrained = 0;
  for (int a = 0; a < d; ++a) {
    if (lambda[a] < 1e-12 * lambda_max) ++unconstrained;
    lambda[a] = std::max(lambda[a], kMinScaledVariance);
  }
  cov_u = eig.eigenvectors() * lambda.asDiagonal() * eig.eigenvectors().transpose();
  est.covariance_ok = computed && unconstrained == 0;
  est.unconstrained_directions = computed ? unconstrained : d;
  est.covariance = Eigen::MatrixXd(d, d);
  for (int a = 0; a < d; ++a)
    for (int b = 0; b < d; ++b)
      est.covariance(a, b) = cov_u(a, b) * scale[pb.free_indices()[a]] * scale[pb.free_indices()[b]];
}

void polish(const CalibrationProblem& pb, PointEstimate& est) {
  Scale scale;
  for (int i = 0; i < kNumParams; ++i) {
    const Prior& pr = pb.priors()[i];
    // |MAP|, but never far below the prior's width: a parameter whose optimum sits near 0 (Kc
    // often does) would otherwise get a vanishing column and lose its variance to the SVD cut.
    scale[i] = std::max({std::abs(est.map[i]), 1e-4 * (pr.upper - pr.lower), 1e-12});
  }
  double u[kNumParams];
  for (int i = 0; i < kNumParams; ++i) u[i] = est.map[i] / scale[i];
  ceres::Problem problem;
  std::vector<ceres::ResidualBlockId> data_blocks;
  auto* wheel = new WheelResiduals{&pb, {}, {}, scale};
  int wheel_rows = 0;
  for (int t = 0; t < pb.num_types(); ++t) {
    if (pb.set(t).is_wheel()) {
      wheel->types.push_back(t);
      wheel->noise_sd.push_back(std::sqrt(pb.correlation_time(t) * est.noise_var[t]));
      wheel_rows += static_cast<int>(pb.set(t).size());
      continue;
    }
    auto* cost = new ceres::DynamicAutoDiffCostFunction<TypeResiduals, 8>(
        new TypeResiduals{&pb, t, std::sqrt(pb.correlation_time(t) * est.noise_var[t]), scale});
    cost->AddParameterBlock(kNumParams);
    cost->SetNumResiduals(static_cast<int>(pb.set(t).size()));
    data_blocks.push_back(problem.AddResidualBlock(cost, nullptr, u));
  }
  if (wheel_rows > 0) {
    ceres::NumericDiffOptions nd;
    nd.relative_step_size = 1e-4;
    auto* cost = new ceres::DynamicNumericDiffCostFunction<WheelResiduals, ceres::CENTRAL>(wheel, ceres::TAKE_OWNERSHIP,
                                                                                           nd);
    cost->AddParameterBlock(kNumParams);
    cost->SetNumResiduals(wheel_rows);
    data_blocks.push_back(problem.AddResidualBlock(cost, nullptr, u));
  } else {
    delete wheel;
  }
  for (int i : pb.free_indices()) {
    const Prior& pr = pb.priors()[i];
    if (pr.kind == Prior::Kind::kNormal || pr.kind == Prior::Kind::kLogNormal)
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<PriorResidual, 1, kNumParams>(new PriorResidual{i, pr, scale[i]}), nullptr,
          u);
    problem.SetParameterLowerBound(u, i, pr.lower / scale[i]);
    problem.SetParameterUpperBound(u, i, pr.upper / scale[i]);
  }
  std::vector<int> fixed;
  for (int i = 0; i < kNumParams; ++i)
    if (pb.priors()[i].fixed()) fixed.push_back(i);
  if (!fixed.empty()) problem.SetManifold(u, new ceres::SubsetManifold(kNumParams, fixed));

  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 200;
  options.function_tolerance = 1e-12;
  options.parameter_tolerance = 1e-12;
  options.num_threads = 1;  // deterministic
  ceres::Solver::Summary summary;
  solve_quietly(options, &problem, &summary);
  est.ceres_report = summary.BriefReport();
  const auto candidate = unscale(u, scale);
  // Keep the polished point only if it is feasible and no worse (Ceres cannot see Kc/r + Kphi > 0).
  if (pb.feasible(candidate) && profile_objective(pb, candidate) <= profile_objective(pb, est.map) + 1e-9)
    est.map = candidate;

  estimate_covariance(pb, problem, data_blocks, scale, u, est);
}

void update_noise(const CalibrationProblem& pb, PointEstimate& est) {
  est.noise_var.resize(pb.num_types());
  est.weighted_rss = 0;
  for (int t = 0; t < pb.num_types(); ++t) {
    const double sse = pb.weighted_sse(t, est.map);
    est.weighted_rss += sse;
    est.noise_var[t] = std::max(sse / static_cast<double>(pb.set(t).size()), 1e-24);
  }
}

}  // namespace

PointEstimate estimate_point(const CalibrationProblem& pb, const PointEstimateOptions& options) {
  PointEstimate est;
  est.map = global_search(pb, options, est.global_evaluations);
  update_noise(pb, est);
  for (int round = 0; round < options.polish_rounds && pb.dim() > 0; ++round) {
    polish(pb, est);
    update_noise(pb, est);
  }
  est.x = pb.reduce(est.map);
  if (pb.dim() == 0) est.covariance = Eigen::MatrixXd::Zero(0, 0);
  return est;
}

}  // namespace terracal::bayes
