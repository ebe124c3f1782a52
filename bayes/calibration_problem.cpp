#include "bayes/calibration_problem.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <map>
#include <memory>

#include <omp.h>

#include <fmt/format.h>

#include "bayes/correlation_time.hpp"
#include "core/concurrent_jobs.hpp"
#include "core/errors.hpp"
#include "lowfi/scm_steady_wheel.hpp"

namespace terracal::bayes {
namespace {

// Threads for the slips of one wheel prediction: the OpenMP threads (OMP_NUM_THREADS, or the cores)
// that the calling team (the chains, one per thread) leaves idle, shared among its threads. 4 chains
// with 16 threads give each 4; with 2 the slips run in order on the chain's own thread. Inside the
// chains' parallel region omp_get_max_threads() is still the whole budget (it is inherited).
int slip_threads() { return std::max(1, omp_get_max_threads() / std::max(1, omp_get_num_threads())); }
// The calling thread's workers for those slips: a slip takes tens of microseconds, about what
// starting a thread costs, so the threads stay between predictions.
WorkerPool& slip_pool() {
  thread_local std::unique_ptr<WorkerPool> pool;
  const int width = slip_threads();
  if (!pool || pool->width() != width) pool = std::make_unique<WorkerPool>(width);
  return *pool;
}
constexpr double kNegInf = -std::numeric_limits<double>::infinity();
// Defaults for parameters the data cannot identify (Chrono's "soft" SCM preset values).
constexpr double kDefaultCohesion = 0.0, kDefaultFriction = 30.0, kDefaultJanosi = 0.01;
// Without wheel curves S is not identified; it is fixed at Lyasko's value and left out of the outputs.
constexpr double kDefaultSlipSinkage = 1.5;
// The steady wheel's quadrature tolerance. At 1e-5 the outputs are within 5 mN (DBP, torque in N m)
// and 1 micrometre (sinkage) of those at 1e-10, for a 108 kg wheel of r = 0.47 m over slips 0-0.8 on
// the 2022 soil's set with Kc, n, S and Ke varied around it (0.05 ms a slip on the dev VM): far below
// the data's scatter and the numerical derivatives' relative step of 1e-4 (point_estimate.cpp).
constexpr double kWheelTolerance = 1e-5;
std::atomic<long> next_problem_id{0};
}  // namespace

CalibrationProblem::CalibrationProblem(const PlateData& plate, const std::optional<ShearData>& shear, Priors priors,
                                       NoiseModel noise, const std::optional<WheelData>& wheel,
                                       AnnulusLaw annulus, double elastic_stiffness)
    : priors_(priors), noise_(noise), elastic_given_(elastic_stiffness), annulus_(annulus), id_(next_problem_id++) {
  if (!(std::isfinite(elastic_stiffness) && elastic_stiffness >= 0))
    throw InputError(fmt::format("--elastic-stiffness: value {} must be > 0 Pa/m (0: fitted to the plates' unload rows)",
                                 elastic_stiffness));
  if (annulus_ == AnnulusLaw::kScaled && !(shear && wheel))
    throw InputError(fmt::format("--annulus-law scaled: needs annulus-shear curves (--shear) and wheel curves "
                                 "(--wheel); got {}",
                                 shear ? "no wheel curves" : wheel ? "no shear curves" : "neither"));
  for (int i = 0; i < kNumParams; ++i)
    if (priors_[i].fixed()) fixed_[i] = priors_[i].value;

  add_plate(plate);
  radii_ = plate.radii;
  // One plate size: Kc/r + Kphi is known at a single r only, so Kc and Kphi cannot be separated.
  if (radii_.size() < 2 && !priors_[kKc].fixed() && !priors_[kKc].user_given && !priors_[kKphi].user_given)
    fix(kKc, 0.0,
        fmt::format("{}: only one plate radius ({} m): Kc and Kphi cannot be separated; Kc is fixed at 0 "
                    "(give a prior for Kc or Kphi, or a second plate size, to change this)",
                    plate.path, radii_.front()));

  if (shear) {
    add_shear(*shear);
    const bool any_transient =
        std::any_of(shear->points.begin(), shear->points.end(), [](const ShearPoint& p) { return !p.developed; });
    if (!any_transient && !priors_[kJanosi].fixed())
      fix(kJanosi, kDefaultJanosi,
          fmt::format("{}: only fully developed torques (no angle): the Janosi k is not identified; fixed at {} m",
                      shear->path, kDefaultJanosi));
  } else if (!wheel) {  // wheel curves identify c, phi and k too
    if (!priors_[kCohesion].fixed())
      fix(kCohesion, kDefaultCohesion, fmt::format("no shear data: cohesion fixed at {} Pa", kDefaultCohesion));
    if (!priors_[kFriction].fixed())
      fix(kFriction, kDefaultFriction, fmt::format("no shear data: friction angle fixed at {} deg", kDefaultFriction));
    if (!priors_[kJanosi].fixed())
      fix(kJanosi, kDefaultJanosi, fmt::format("no shear data: Janosi k fixed at {} m", kDefaultJanosi));
  }
  if (wheel) {
    add_wheel(*wheel);
  } else {
    leave_out(kSlipSinkage, kDefaultSlipSinkage,
              fmt::format("no wheel data: the prior of S is not used (S is fixed at {}; only single-wheel curves "
                          "identify it)",
                          kDefaultSlipSinkage));
  }
  if (!annulus_scaled()) {
    leave_out(kShearRatio, 1.0, "--annulus-law shared: the prior of R is not used (the annulus's law is the set's)");
    leave_out(kAnnulusJanosi, 0.0,
              "--annulus-law shared: the prior of k_annulus is not used (the annulus's law is the set's)");
  }
  for (int i = 0; i < kNumParams; ++i)
    if (!priors_[i].fixed()) free_.push_back(i);
  elastic_ = fit_elastic_stiffness(plate, noise_ == NoiseModel::kRelative);
  tau_.assign(sets_.size(), 1.0);
  notes_.insert(notes_.end(), elastic_.notes.begin(), elastic_.notes.end());
}

void CalibrationProblem::fix(int i, double value, const std::string& why) {
  priors_[i].kind = Prior::Kind::kFixed;
  priors_[i].value = priors_[i].lower = priors_[i].upper = value;
  fixed_[i] = value;
  notes_.push_back(why);
}

void CalibrationProblem::leave_out(int i, double value, const std::string& why_unused) {
  if (priors_[i].fixed()) return;
  if (priors_[i].user_given) notes_.push_back(why_unused);
  priors_[i] = fixed_prior(value);
  priors_[i].user_given = false;
  fixed_[i] = value;
}

bool CalibrationProblem::reported(int i) const {
  if (i == kSlipSinkage) return has_wheel();
  if (i == kShearRatio || i == kAnnulusJanosi) return annulus_scaled();
  return true;
}

void CalibrationProblem::add_plate(const PlateData& plate) {
  notes_.insert(notes_.end(), plate.notes.begin(), plate.notes.end());
  ObservationSet s;
  s.kind = ObservationSet::Kind::kPlate;
  s.name = "plate";
  s.unit = "N";
  std::map<double, int> curve_of;
  for (const auto& p : plate.points) {
    if (!p.fitted) continue;
    if (!curve_of.count(p.radius)) {
      curve_of[p.radius] = static_cast<int>(s.curve_labels.size());
      s.curve_labels.push_back(fmt::format("plate r = {:g} m", p.radius));
    }
    s.y.push_back(p.force);
    s.r.push_back(p.radius);
    s.log_z.push_back(std::log(p.sinkage));
    s.x_axis.push_back(p.sinkage);
    s.curve.push_back(curve_of[p.radius]);
  }
  set_weights(s);
  index_kernels(s);
  sets_.push_back(std::move(s));
}

void CalibrationProblem::add_shear(const ShearData& shear) {
  notes_.insert(notes_.end(), shear.notes.begin(), shear.notes.end());
  ObservationSet s;
  s.kind = ObservationSet::Kind::kShear;
  s.name = "shear";
  s.unit = "N m";
  std::map<std::tuple<double, double, double>, int> curve_of;
  for (const auto& p : shear.points) {
    const auto key = std::make_tuple(p.inner_radius, p.outer_radius, p.normal_load);
    if (!curve_of.count(key)) {
      curve_of[key] = static_cast<int>(s.curve_labels.size());
      s.curve_labels.push_back(fmt::format("W = {:g} N", p.normal_load));
    }
    s.y.push_back(p.torque);
    s.r_in.push_back(p.inner_radius);
    s.r_out.push_back(p.outer_radius);
    s.load.push_back(p.normal_load);
    s.angle.push_back(p.developed ? -1.0 : p.angle);
    s.x_axis.push_back(p.developed ? std::numeric_limits<double>::quiet_NaN() : p.angle);
    s.curve.push_back(curve_of[key]);
  }
  set_weights(s);
  index_kernels(s);
  sets_.push_back(std::move(s));
}

void CalibrationProblem::add_wheel(const WheelData& wheel) {
  wheel_ = wheel;
  notes_.insert(notes_.end(), wheel.notes.begin(), wheel.notes.end());
  const std::pair<ObservationSet::Kind, const char*> channels[] = {{ObservationSet::Kind::kWheelDbp, "wheel_dbp"},
                                                                   {ObservationSet::Kind::kWheelTorque, "wheel_torque"},
                                                                   {ObservationSet::Kind::kWheelSinkage, "wheel_sinkage"}};
  for (const auto& [kind, name] : channels) {
    ObservationSet s;
    s.kind = kind;
    s.name = name;
    s.unit = kind == ObservationSet::Kind::kWheelDbp ? "N" : kind == ObservationSet::Kind::kWheelTorque ? "N m" : "m";
    std::map<double, int> curve_of;
    for (const WheelPoint& p : wheel.points) {
      if (!curve_of.count(p.load)) {
        curve_of[p.load] = static_cast<int>(s.curve_labels.size());
        s.curve_labels.push_back(fmt::format("W = {:g} N", p.load));
      }
      s.y.push_back(kind == ObservationSet::Kind::kWheelDbp      ? p.dbp
                    : kind == ObservationSet::Kind::kWheelTorque ? p.torque
                                                                 : p.sinkage);
      s.load.push_back(p.load);
      s.x_axis.push_back(p.slip);
      s.curve.push_back(curve_of[p.load]);
    }
    s.w.assign(s.size(), 1.0);  // absolute: each channel's own scale carries its units
    sets_.push_back(std::move(s));
  }
}

lowfi::ScmSoil CalibrationProblem::soil_of(const ParamVector& p) const {
  lowfi::ScmSoil soil;
  soil.Kc = p[kKc];
  soil.Kphi = p[kKphi];
  soil.n = p[kN];
  soil.cohesion = p[kCohesion];
  soil.friction_deg = p[kFriction];
  soil.janosi_k = p[kJanosi];
  soil.elastic_stiffness = set_elastic_stiffness();
  soil.damping = kDefaultDamping;
  soil.slip_sinkage.S = p[kSlipSinkage];
  return soil;
}

const WheelPrediction& CalibrationProblem::predict_wheel(const ParamVector& p) const {
  struct Cache {
    long owner = -1;
    ParamVector p{};
    WheelPrediction pred;
  };
  thread_local Cache cache;
  if (cache.owner == id_ && cache.p == p) return cache.pred;
  const WheelData& d = *wheel_;
  const lowfi::WongReeceWheel rim{d.wheel.radius, d.wheel.width};
  lowfi::ScmSteadyWheelOptions opt;
  opt.angular_velocity = d.wheel.angular_velocity;
  opt.slip_sinkage = p[kSlipSinkage] > 0;
  opt.rel_tol = kWheelTolerance;
  const lowfi::ScmSoil soil = soil_of(p);
  const std::size_t n = d.points.size();
  WheelPrediction& out = cache.pred;
  out.dbp.assign(n, std::numeric_limits<double>::quiet_NaN());
  out.torque = out.sinkage = out.dbp;
  // The slips are independent of each other: they run at once on the cores the chains leave idle
  // (the predictions do not depend on how many).
  try {
    slip_pool().run(n, [&](std::size_t i) {
      const lowfi::WongReeceResult r = lowfi::scm_steady_wheel(soil, rim, d.points[i].load, d.points[i].slip, opt);
      out.dbp[i] = r.dbp;
      out.torque[i] = r.torque;
      out.sinkage[i] = r.sinkage;
    });
  } catch (const std::exception&) {
    // No steady state for this set (a soil outside its range, a wheel sinking past its axle): the
    // NaN predictions reject it.
  }
  cache.owner = id_;
  cache.p = p;
  return out;
}

void CalibrationProblem::index_kernels(ObservationSet& s) {
  std::map<std::tuple<double, double, double>, int> index;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const auto key = s.kind == ObservationSet::Kind::kPlate ? std::make_tuple(s.log_z[i], 0.0, 0.0)
                                                            : std::make_tuple(s.r_in[i], s.r_out[i], s.angle[i]);
    auto [it, inserted] = index.try_emplace(key, static_cast<int>(index.size()));
    if (inserted) {
      if (s.kind == ObservationSet::Kind::kPlate) {
        s.kernel_log_z.push_back(s.log_z[i]);
      } else {
        s.kernel_r_in.push_back(s.r_in[i]);
        s.kernel_r_out.push_back(s.r_out[i]);
        s.kernel_angle.push_back(s.angle[i]);
      }
    }
    s.kernel.push_back(it->second);
  }
}

void CalibrationProblem::set_weights(ObservationSet& s) const {
  s.w.assign(s.size(), 1.0);
  if (noise_ == NoiseModel::kAbsolute) return;
  std::vector<double> curve_max(s.curve_labels.size(), 0.0);
  for (std::size_t i = 0; i < s.size(); ++i) curve_max[s.curve[i]] = std::max(curve_max[s.curve[i]], std::abs(s.y[i]));
  for (std::size_t i = 0; i < s.size(); ++i) s.w[i] = std::max(std::abs(s.y[i]), 0.01 * curve_max[s.curve[i]]);
  for (double& w : s.w)
    if (!(w > 0)) w = 1.0;  // an all-zero curve: fall back to absolute weights
}

ParamVector CalibrationProblem::expand(const Eigen::VectorXd& x) const {
  ParamVector p = fixed_;
  for (std::size_t j = 0; j < free_.size(); ++j) p[free_[j]] = x[static_cast<int>(j)];
  return p;
}

Eigen::VectorXd CalibrationProblem::reduce(const ParamVector& p) const {
  Eigen::VectorXd x(dim());
  for (std::size_t j = 0; j < free_.size(); ++j) x[static_cast<int>(j)] = p[free_[j]];
  return x;
}

std::vector<double> CalibrationProblem::predict_all(int t, const ParamVector& p) const {
  std::vector<double> f(sets_[t].size());
  predict_set(t, p.data(), f.data());
  return f;
}

double CalibrationProblem::weighted_sse(int t, const ParamVector& p) const {
  const ObservationSet& s = sets_[t];
  thread_local std::vector<double> f;
  f.resize(s.size());
  predict_set(t, p.data(), f.data());
  double sse = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double r = (s.y[i] - f[i]) / s.w[i];
    sse += r * r;
  }
  return std::isfinite(sse) ? sse : std::numeric_limits<double>::quiet_NaN();
}

bool CalibrationProblem::feasible(const ParamVector& p) const {
  for (int i = 0; i < kNumParams; ++i)
    if (!priors_[i].fixed() && !priors_[i].contains(p[i])) return false;
  for (double r : radii_)
    if (!(p[kKc] / r + p[kKphi] > 0)) return false;
  return true;
}

double CalibrationProblem::log_prior(const ParamVector& p) const {
  if (!feasible(p)) return kNegInf;
  double lp = 0;
  for (int i : free_) lp += priors_[i].log_density(p[i]);
  return lp;
}

double CalibrationProblem::log_posterior(const ParamVector& p, const Eigen::VectorXd& noise_var) const {
  const double lp = log_prior(p);
  if (lp == kNegInf) return kNegInf;
  double ll = lp;
  for (int t = 0; t < num_types(); ++t) {
    const double n = static_cast<double>(sets_[t].size());
    // Jeffreys prior on s^2 contributes -log s^2.
    ll += -0.5 * weighted_sse(t, p) / (tau_[t] * noise_var[t]) - (0.5 * n / tau_[t] + 1.0) * std::log(noise_var[t]);
  }
  return ll;
}

void CalibrationProblem::draw_noise(const ParamVector& p, Eigen::VectorXd& noise_var, Rng& rng) const {
  for (int t = 0; t < num_types(); ++t) {
    // s^2 | theta ~ InvGamma(N/2, SSE/2): draw Gamma(N/2, 1) g and set s^2 = (SSE/2) / g.
    const double sse = weighted_sse(t, p);
    noise_var[t] = 0.5 * sse / tau_[t] / rng.gamma(0.5 * effective_rows(t));
  }
}

std::vector<double> CalibrationProblem::correlation_times(const ParamVector& p) const {
  std::vector<double> tau(sets_.size());
  for (int t = 0; t < num_types(); ++t) {
    const ObservationSet& s = sets_[t];
    const std::vector<double> f = predict_all(t, p);
    std::vector<double> r(s.size());
    for (std::size_t i = 0; i < s.size(); ++i) r[i] = (s.y[i] - f[i]) / s.w[i];
    tau[t] = bayes::correlation_time(r, s.curve);
  }
  return tau;
}

void CalibrationProblem::set_correlation_times(const std::vector<double>& tau) {
  if (tau.size() != sets_.size()) throw InputError("calibration: one correlation time per test type");
  for (std::size_t t = 0; t < tau.size(); ++t)
    if (!(std::isfinite(tau[t]) && tau[t] >= 1))
      throw InputError(fmt::format("calibration: test type {}: correlation time {} must be finite and >= 1",
                                   sets_[t].name, tau[t]));
  tau_ = tau;
}

Target CalibrationProblem::target() const {
  Target t;
  t.dim = dim();
  t.nuisance_dim = num_types();
  t.lower.resize(dim());
  t.upper.resize(dim());
  for (int j = 0; j < dim(); ++j) {
    t.lower[j] = priors_[free_[j]].lower;
    t.upper[j] = priors_[free_[j]].upper;
  }
  t.log_density = [this](const Eigen::VectorXd& x, const Eigen::VectorXd& nv) { return log_posterior(expand(x), nv); };
  t.gibbs = [this](const Eigen::VectorXd& x, Eigen::VectorXd& nv, Rng& rng) { draw_noise(expand(x), nv, rng); };
  return t;
}

}  // namespace terracal::bayes
