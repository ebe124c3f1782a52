#pragma once
// The calibration problem: observations, forward models, priors and the noise model, assembled
// once. Everything downstream (global search, least squares, samplers, outputs) asks this class
// for predictions, residuals and densities, so the statistics live in one place.
//
// Noise model. Each test type t (plate force, shear torque) has its own unknown noise scale s_t:
//   y_i = f_i(theta) + s_t w_i eps_i,  eps_i ~ N(0, 1),
// with fixed weights w_i taken from the data: relative noise (default) w_i = max(|y_i|, 1 % of the
// largest |y| of its curve) -- measurement error grows with the signal, and the floor keeps the
// weight finite at zero force -- or absolute noise w_i = 1. The variances s_t^2 get the Jeffreys
// prior p(s^2) ~ 1/s^2, so given theta they are inverse-gamma(N_t/2, SSE_t/2): a conjugate Gibbs step.
// With correlation times tau_t (set_correlation_times; bayes/correlation_time.hpp) type t counts as
// N_t / tau_t rows: its likelihood is raised to 1 / tau_t, s_t^2 | theta ~ IG(N_t/(2 tau_t), SSE_t/(2 tau_t)).
//
// Single-wheel curves (optional) add three test types, drawbar pull, torque and sinkage, each with
// its own scale and absolute weights (a pull crosses zero near slip 0, where relative weights would
// blow up). Their predictions come from the steady SCM wheel (lowfi/scm_steady_wheel.hpp), in double
// only, once per parameter set for all three; they free Lyasko's slip-sinkage S, fixed otherwise.
//
// The annulus's law (AnnulusLaw). Shared (default): the annulus torque follows the set's own c, phi
// and k. Scaled (bevameter and wheel curves together): the annulus follows the set's law with its
// strength divided by a fitted ratio R and its own Janosi k, tau_annulus = (c + p tan phi) / R
// (1 - e^{-j/k_annulus}). The annulus then tells the set only how its shear strength grows with the
// normal load (c against tan phi); the wheel sets the strength's level and k. CRM's Drucker-Prager
// soil mobilises a different Mohr-Coulomb strength under a thin ring than under a wheel
// (docs/decisions.md, "Annulus law").
//
// SCM's elastic stiffness Ke is fitted to the plates' unload rows (elastic_stiffness.hpp) unless the
// caller gives the set's own (`elastic_stiffness` > 0): the plates' fit is then still made and
// reported, but the set, and the steady wheel through which wheel curves see it, use the given one.
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <Eigen/Dense>

#include "bayes/elastic_stiffness.hpp"
#include "bayes/forward_models.hpp"
#include "bayes/observations.hpp"
#include "bayes/priors.hpp"
#include "bayes/target.hpp"
#include "bayes/wheel_observations.hpp"
#include "lowfi/scm_soil.hpp"

namespace terracal::bayes {

enum class NoiseModel { kRelative, kAbsolute };
enum class AnnulusLaw { kShared, kScaled };

// Chrono's default SCM damping: quasi-static bevameter curves do not identify it. (The default
// elastic stiffness, used when the plate data have no unloading, is in elastic_stiffness.hpp.)
inline constexpr double kDefaultDamping = 3e4;  // Pa s/m

// The fitted observations of one test type, flattened.
struct ObservationSet {
  enum class Kind { kPlate, kShear, kWheelDbp, kWheelTorque, kWheelSinkage };
  Kind kind = Kind::kPlate;
  std::string name;          // "plate", "shear", "wheel_dbp", "wheel_torque", "wheel_sinkage"
  std::string unit;          // "N", "N m" or "m"
  std::vector<double> y, w;  // observed value, noise weight
  // Plate rows: radius, log sinkage. Shear rows: radii, load, angle (developed rows: angle < 0).
  // Wheel rows: load, slip (x_axis), in the order of CalibrationProblem::wheel_rows().
  std::vector<double> r, log_z, r_in, r_out, load, angle;
  std::vector<double> x_axis;  // sinkage, angle or slip, for plots
  std::vector<int> curve;      // which curve (plate radius / shear load) a row belongs to
  std::vector<std::string> curve_labels;
  // Rows share kernels: plates repeat sinkages (z^n), shear tests repeat angles (the development
  // integral). kernel[i] indexes the distinct kernels; kernel_log_z / kernel_r_in, kernel_r_out,
  // kernel_angle (< 0: fully developed) describe them.
  std::vector<int> kernel;
  std::vector<double> kernel_log_z, kernel_r_in, kernel_r_out, kernel_angle;
  std::size_t size() const { return y.size(); }
  std::size_t kernels() const { return kind == Kind::kPlate ? kernel_log_z.size() : kernel_angle.size(); }
  bool is_wheel() const { return kind != Kind::kPlate && kind != Kind::kShear; }
};

// The steady SCM wheel's predictions at every wheel row, for one parameter set (NaN where the model
// has no steady state, e.g. a wheel that would sink past its axle).
struct WheelPrediction {
  std::vector<double> dbp, torque, sinkage;
  const std::vector<double>& channel(ObservationSet::Kind k) const {
    return k == ObservationSet::Kind::kWheelDbp ? dbp : k == ObservationSet::Kind::kWheelTorque ? torque : sinkage;
  }
};

class CalibrationProblem {
 public:
  CalibrationProblem(const PlateData& plate, const std::optional<ShearData>& shear, Priors priors,
                     NoiseModel noise = NoiseModel::kRelative, const std::optional<WheelData>& wheel = std::nullopt,
                     AnnulusLaw annulus = AnnulusLaw::kShared, double elastic_stiffness = 0);

  // Free (inferred) parameters, in ParamVector order; the others are fixed.
  const std::vector<int>& free_indices() const { return free_; }
  int dim() const { return static_cast<int>(free_.size()); }
  ParamVector expand(const Eigen::VectorXd& x) const;
  Eigen::VectorXd reduce(const ParamVector& p) const;
  const ParamVector& fixed_values() const { return fixed_; }

  int num_types() const { return static_cast<int>(sets_.size()); }
  const ObservationSet& set(int t) const { return sets_[t]; }
  const Priors& priors() const { return priors_; }
  NoiseModel noise_model() const { return noise_; }
  const std::vector<double>& plate_radii() const { return radii_; }
  // Things the user must know: parameters fixed because the data cannot identify them, etc.
  const std::vector<std::string>& notes() const { return notes_; }
  // SCM's elastic stiffness from the unload/reload rows: a separate linear least-squares problem
  // (elastic_stiffness.hpp), solved once here; its notes are among notes().
  const ElasticFit& elastic() const { return elastic_; }
  // The set's Ke: the caller's if given, else the plates' fit (or Chrono's default).
  bool elastic_given() const { return elastic_given_ > 0; }
  double set_elastic_stiffness() const { return elastic_given() ? elastic_given_ : elastic_.ke; }

  // Wheel data: whether there are any, the wheel, and the SCM set a parameter vector stands for
  // (with the fitted Ke, Chrono's damping, and S as its slip sinkage).
  bool has_wheel() const { return wheel_.has_value(); }
  // Whether the annulus has its own strength ratio R and Janosi k (AnnulusLaw::kScaled).
  bool annulus_scaled() const { return annulus_ == AnnulusLaw::kScaled; }
  // Whether parameter i belongs in the outputs: S with wheel curves, R and k_annulus when scaled.
  bool reported(int i) const;
  const WheelGeometry& wheel() const { return wheel_->wheel; }
  lowfi::ScmSoil soil_of(const ParamVector& p) const;
  // The steady wheel at every wheel row; the last result is kept per thread, so that the three wheel
  // types (and the Gibbs step after a density) pay for one evaluation.
  const WheelPrediction& predict_wheel(const ParamVector& p) const;

  // Predictions of every row of test type t into out[0..size); p is a full parameter array of scalar
  // T (double, or a Ceres Jet for the bevameter types; the wheel types take double only). Each
  // distinct kernel is evaluated once.
  template <typename T>
  void predict_set(int t, const T* p, T* out) const {
    const ObservationSet& s = sets_[t];
    if (s.is_wheel()) {
      if constexpr (std::is_same_v<T, double>) {
        ParamVector pv;
        for (int i = 0; i < kNumParams; ++i) pv[i] = p[i];
        const std::vector<double>& f = predict_wheel(pv).channel(s.kind);
        for (std::size_t i = 0; i < s.size(); ++i) out[i] = f[i];
        return;
      } else {
        throw std::logic_error("the steady wheel has no automatic derivatives: differentiate it numerically");
      }
    }
    thread_local std::vector<T> kern;
    kern.resize(s.kernels());
    if (s.kind == ObservationSet::Kind::kPlate) {
      for (std::size_t k = 0; k < kern.size(); ++k) kern[k] = sinkage_power(s.kernel_log_z[k], p[kN]);
      for (std::size_t i = 0; i < s.size(); ++i) out[i] = plate_stiffness(s.r[i], p[kKc], p[kKphi]) * kern[s.kernel[i]];
      return;
    }
    const bool scaled = annulus_scaled();
    const T& k = scaled ? p[kAnnulusJanosi] : p[kJanosi];
    for (std::size_t j = 0; j < kern.size(); ++j)
      kern[j] = s.kernel_angle[j] < 0 ? T(annulus_development_full(s.kernel_r_in[j], s.kernel_r_out[j]))
                                      : annulus_development(s.kernel_r_in[j], s.kernel_r_out[j], s.kernel_angle[j], k);
    const T tan_phi = tan_degrees(p[kFriction]);
    for (std::size_t i = 0; i < s.size(); ++i)
      out[i] = annulus_shear_strength(s.r_in[i], s.r_out[i], s.load[i], p[kCohesion], tan_phi) * kern[s.kernel[i]];
    if (scaled)
      for (std::size_t i = 0; i < s.size(); ++i) out[i] /= p[kShearRatio];
  }
  std::vector<double> predict_all(int t, const ParamVector& p) const;

  // Sum of squared weighted residuals ((y - f)/w)^2 of test type t (NaN if a prediction is not finite).
  double weighted_sse(int t, const ParamVector& p) const;
  // Each type's residual correlation time at p (1 <= tau <= N/10), and setting them (default all 1:
  // white noise). effective_rows(t) = N_t / tau_t.
  std::vector<double> correlation_times(const ParamVector& p) const;
  void set_correlation_times(const std::vector<double>& tau);
  double correlation_time(int t) const { return tau_[t]; }
  double effective_rows(int t) const { return static_cast<double>(sets_[t].size()) / tau_[t]; }
  // Inside every prior's support, and Kc/r + Kphi > 0 for every plate radius in the data.
  bool feasible(const ParamVector& p) const;
  double log_prior(const ParamVector& p) const;
  // log p(theta, s^2 | y) up to a constant; noise_var holds s_t^2 per test type.
  double log_posterior(const ParamVector& p, const Eigen::VectorXd& noise_var) const;
  // The sampler's view: x = free parameters, nuisance = noise variances with their Gibbs step.
  Target target() const;
  // Draws s_t^2 | theta (inverse gamma); used by target().gibbs.
  void draw_noise(const ParamVector& p, Eigen::VectorXd& noise_var, Rng& rng) const;

 private:
  void add_plate(const PlateData& plate);
  void add_shear(const ShearData& shear);
  void add_wheel(const WheelData& wheel);
  void fix(int i, double value, const std::string& why);
  // Parameter i is not part of this problem: fixed at `value`, a user's prior for it noted as unused.
  void leave_out(int i, double value, const std::string& why_unused);
  void set_weights(ObservationSet& s) const;
  static void index_kernels(ObservationSet& s);

  Priors priors_;
  NoiseModel noise_;
  std::vector<ObservationSet> sets_;
  std::vector<double> radii_;
  std::vector<int> free_;
  ParamVector fixed_{};
  std::vector<std::string> notes_;
  ElasticFit elastic_;
  double elastic_given_ = 0;  // Pa/m; 0: the set takes the plates' fit
  std::optional<WheelData> wheel_;
  AnnulusLaw annulus_ = AnnulusLaw::kShared;
  long id_ = 0;  // tells this problem's cached wheel predictions from another's
  std::vector<double> tau_;  // per type: residual correlation time (1: white noise)
};

}  // namespace terracal::bayes
