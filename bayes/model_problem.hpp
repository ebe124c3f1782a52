#pragma once
// A calibration problem whose forward model is a simulation (a reduced-order vehicle, a wheel run):
// named parameters with priors, observed channels, and a forward model that evaluates many
// parameter vectors in one call (CPU threads or one GPU batch). The calibrator knows no vehicle:
// the caller (apps/) wraps its simulation as a BatchForward.
//
// Noise model. Each channel c (a signal such as yaw rate) has its own unknown noise variance s_c^2:
//   y_i = f_i(theta) + s_c eps_i,  eps_i ~ N(0, 1),
// absolute noise in the channel's unit; s_c^2 has the Jeffreys prior 1/s^2, so given theta it is
// inverse-gamma(N_c/2, SSE_c/2): a conjugate Gibbs step, as for SCM (calibration_problem.hpp).
//
// Correlated residuals. A model that cannot reproduce its reference leaves residuals that vary
// slowly along a run (at 100 samples per second, neighbouring rows miss by nearly the same amount),
// and counting each row as an independent observation makes the posterior far too narrow. With
// set_correlation_times, channel c counts as N_c / tau_c independent rows: its likelihood is raised
// to the power 1 / tau_c (s_c^2 | theta ~ inverse-gamma(N_c / (2 tau_c), SSE_c / (2 tau_c))), where
// tau_c = (1 + rho) / (1 - rho) is the integrated correlation time of an AR(1) process with the
// residuals' lag-one correlation rho (correlation_times). tau_c = 1 is the white-noise model.
//
// Failures. A run that fails (diverges, throws, returns a non-finite value) makes its point's log
// density NaN: samplers reject it and count it; the point estimate treats it as infinitely bad.
#include <atomic>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "bayes/priors.hpp"
#include "bayes/target.hpp"

namespace terracal::bayes {

struct ModelParameter {
  std::string name, unit;
  Prior prior;           // its support bounds the search; a fixed prior is not allowed here
  double initial = 0.0;  // where the global search starts (the preset's value)
};

struct ModelChannel {
  std::string name, unit;  // "yaw_rate", "rad/s"
  std::vector<double> y;   // observed values, the rows of every reference in turn
  std::vector<double> x;   // the abscissa of each row (time), for plots
  std::vector<int> curve;  // which reference a row belongs to
  std::vector<std::string> curve_labels;
  std::size_t size() const { return y.size(); }
};

// out[i]: the predictions of every channel's rows for params[i], the channels in order and each
// channel's rows as in ModelChannel::y; an empty vector when that run failed.
using BatchForward =
    std::function<void(const std::vector<Eigen::VectorXd>& params, std::vector<std::vector<double>>& out)>;

// out[i]: each channel's SSE for params[i] (ModelProblem::sse_of of its predictions, to round-off),
// an empty vector when that run failed. A forward model that compares where it runs (a GPU batch)
// returns these few numbers per run instead of its predictions.
using BatchSse = std::function<void(const std::vector<Eigen::VectorXd>& params, std::vector<std::vector<double>>& out)>;

class ModelProblem {
 public:
  // Throws InputError for no parameters, a fixed or inverted prior, an empty channel, or channel
  // vectors of different lengths.
  ModelProblem(std::vector<ModelParameter> parameters, std::vector<ModelChannel> channels, BatchForward forward);

  int dim() const { return static_cast<int>(parameters_.size()); }
  int num_channels() const { return static_cast<int>(channels_.size()); }
  const ModelParameter& parameter(int j) const { return parameters_[j]; }
  const ModelChannel& channel(int c) const { return channels_[c]; }
  std::size_t rows() const { return rows_; }

  double log_prior(const Eigen::VectorXd& x) const;  // -inf outside the support
  // Every channel's predictions for each x (one batch); empty for a failed run or a point outside
  // the prior's support (not run).
  std::vector<std::vector<double>> predict(const std::vector<Eigen::VectorXd>& xs) const;
  // SSE per channel for each x (one batch); NaN entries for a failed run or a point outside the
  // support. Results are remembered, so a Gibbs step at a point just evaluated costs no run.
  std::vector<Eigen::VectorXd> sse(const std::vector<Eigen::VectorXd>& xs) const;
  // From now on sse() asks `f` for the sums instead of the predictions (predict() is unchanged).
  void set_batch_sse(BatchSse f) { batch_sse_ = std::move(f); }
  // The per-channel SSE of one prediction vector.
  Eigen::VectorXd sse_of(const std::vector<double>& prediction) const;
  // log p(theta, s^2 | y) up to a constant, from a point's SSE.
  double log_posterior(const Eigen::VectorXd& x, const Eigen::VectorXd& sse, const Eigen::VectorXd& noise_var) const;
  // Each channel's residual correlation time at x (one run): (1 + rho) / (1 - rho), rho the lag-one
  // correlation of the residuals within each reference, pooled; at least 1 and at most N_c / 10
  // (so that every channel keeps ten independent rows). Throws RunError when the run fails.
  Eigen::VectorXd correlation_times(const Eigen::VectorXd& x) const;
  // Counts channel c as N_c / tau[c] rows from now on (default: every tau 1). Throws InputError for
  // a tau below 1 or non-finite.
  void set_correlation_times(const Eigen::VectorXd& tau);
  double effective_rows(int c) const { return static_cast<double>(channels_[c].size()) / tau_[c]; }
  double correlation_time(int c) const { return tau_[c]; }
  // The sampler's view: x = the parameters, nuisance = the noise variances with their Gibbs step;
  // log_density_batch evaluates a batch in one forward call.
  Target target() const;

  long runs() const { return runs_; }                // forward runs asked for
  long failed_runs() const { return failed_runs_; }  // of which failed

 private:
  std::vector<ModelParameter> parameters_;
  std::vector<ModelChannel> channels_;
  BatchForward forward_;
  BatchSse batch_sse_;  // optional
  // xs inside the prior's support (only these are run), and where each stands in xs.
  std::vector<Eigen::VectorXd> inside_support(const std::vector<Eigen::VectorXd>& xs,
                                              std::vector<std::size_t>& where) const;
  // SSE per channel of each x through batch_sse_; NaN entries for a failed run or a point outside.
  std::vector<Eigen::VectorXd> run_sse(const std::vector<Eigen::VectorXd>& xs) const;
  std::size_t rows_ = 0;
  std::vector<std::size_t> offset_;  // first row of each channel in a prediction vector
  Eigen::VectorXd tau_;              // each channel's residual correlation time (1: white noise)
  mutable std::mutex cache_mutex_;
  mutable std::map<std::vector<double>, Eigen::VectorXd> cache_;
  mutable std::atomic<long> runs_{0}, failed_runs_{0};
};

}  // namespace terracal::bayes
