#include "bayes/model_problem.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <fmt/format.h>

#include "bayes/correlation_time.hpp"
#include "core/errors.hpp"

namespace terracal::bayes {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kNegInf = -std::numeric_limits<double>::infinity();
// Remembered SSEs; the map is cleared when it reaches this many points (a few MB).
constexpr std::size_t kCacheLimit = 20000;

std::vector<double> key_of(const Eigen::VectorXd& x) { return {x.data(), x.data() + x.size()}; }

}  // namespace

ModelProblem::ModelProblem(std::vector<ModelParameter> parameters, std::vector<ModelChannel> channels,
                           BatchForward forward)
    : parameters_(std::move(parameters)), channels_(std::move(channels)), forward_(std::move(forward)) {
  if (parameters_.empty()) throw InputError("calibration: no parameter to fit");
  if (channels_.empty()) throw InputError("calibration: no channel to compare");
  for (const auto& p : parameters_) {
    if (p.prior.fixed()) throw InputError(fmt::format("calibration: parameter {} is fixed, not fitted", p.name));
    if (!(p.prior.lower < p.prior.upper))
      throw InputError(fmt::format("calibration: parameter {}: lower bound {} is not below upper bound {}", p.name,
                                   p.prior.lower, p.prior.upper));
  }
  for (const auto& c : channels_) {
    if (c.y.empty()) throw InputError(fmt::format("calibration: channel {} has no rows", c.name));
    if (c.x.size() != c.y.size() || c.curve.size() != c.y.size())
      throw InputError(fmt::format("calibration: channel {}: y, x and curve differ in length", c.name));
    offset_.push_back(rows_);
    rows_ += c.size();
  }
  tau_ = Eigen::VectorXd::Ones(num_channels());
}

Eigen::VectorXd ModelProblem::correlation_times(const Eigen::VectorXd& x) const {
  const auto f = predict({x});
  if (f[0].empty()) throw RunError("calibration: the run at the least-squares point failed");
  Eigen::VectorXd tau(num_channels());
  for (int c = 0; c < num_channels(); ++c) {
    const ModelChannel& ch = channels_[c];
    std::vector<double> r(ch.size());
    for (std::size_t i = 0; i < ch.size(); ++i) r[i] = ch.y[i] - f[0][offset_[c] + i];
    tau[c] = bayes::correlation_time(r, ch.curve);
  }
  return tau;
}

void ModelProblem::set_correlation_times(const Eigen::VectorXd& tau) {
  if (tau.size() != num_channels()) throw InputError("calibration: one correlation time per channel");
  for (int c = 0; c < num_channels(); ++c)
    if (!(std::isfinite(tau[c]) && tau[c] >= 1))
      throw InputError(fmt::format("calibration: channel {}: correlation time {} must be finite and >= 1",
                                   channels_[c].name, tau[c]));
  tau_ = tau;
}

double ModelProblem::log_prior(const Eigen::VectorXd& x) const {
  double lp = 0;
  for (int j = 0; j < dim(); ++j) {
    if (!parameters_[j].prior.contains(x[j])) return kNegInf;
    lp += parameters_[j].prior.log_density(x[j]);
  }
  return lp;
}

// Only points inside the support are run: a simulation outside its parameters' range may not even
// start.
std::vector<Eigen::VectorXd> ModelProblem::inside_support(const std::vector<Eigen::VectorXd>& xs,
                                                          std::vector<std::size_t>& where) const {
  std::vector<Eigen::VectorXd> inside;
  where.clear();
  for (std::size_t i = 0; i < xs.size(); ++i)
    if (std::isfinite(log_prior(xs[i]))) {
      inside.push_back(xs[i]);
      where.push_back(i);
    }
  return inside;
}

std::vector<Eigen::VectorXd> ModelProblem::run_sse(const std::vector<Eigen::VectorXd>& xs) const {
  std::vector<std::size_t> where;
  const std::vector<Eigen::VectorXd> inside = inside_support(xs, where);
  std::vector<Eigen::VectorXd> out(xs.size(), Eigen::VectorXd::Constant(num_channels(), kNaN));
  if (inside.empty()) return out;
  runs_ += static_cast<long>(inside.size());
  std::vector<std::vector<double>> ran;
  try {
    batch_sse_(inside, ran);
  } catch (const std::exception&) {
    ran.assign(inside.size(), {});
  }
  for (std::size_t k = 0; k < inside.size(); ++k) {
    bool ok = k < ran.size() && ran[k].size() == static_cast<std::size_t>(num_channels());
    for (int c = 0; ok && c < num_channels(); ++c) ok = std::isfinite(ran[k][c]);
    if (ok)
      out[where[k]] = Eigen::Map<const Eigen::VectorXd>(ran[k].data(), num_channels());
    else
      ++failed_runs_;
  }
  return out;
}

std::vector<std::vector<double>> ModelProblem::predict(const std::vector<Eigen::VectorXd>& xs) const {
  std::vector<std::size_t> where;
  const std::vector<Eigen::VectorXd> inside = inside_support(xs, where);
  std::vector<std::vector<double>> out(xs.size()), ran;
  if (inside.empty()) return out;
  runs_ += static_cast<long>(inside.size());
  try {
    forward_(inside, ran);
  } catch (const std::exception&) {
    ran.assign(inside.size(), {});
  }
  for (std::size_t k = 0; k < inside.size(); ++k) {
    bool ok = k < ran.size() && ran[k].size() == rows_;
    for (std::size_t r = 0; ok && r < rows_; ++r) ok = std::isfinite(ran[k][r]);
    if (ok)
      out[where[k]] = std::move(ran[k]);
    else
      ++failed_runs_;
  }
  return out;
}

Eigen::VectorXd ModelProblem::sse_of(const std::vector<double>& f) const {
  Eigen::VectorXd s = Eigen::VectorXd::Constant(num_channels(), kNaN);
  if (f.size() != rows_) return s;
  for (int c = 0; c < num_channels(); ++c) {
    double sum = 0;
    for (std::size_t i = 0; i < channels_[c].size(); ++i) {
      const double r = channels_[c].y[i] - f[offset_[c] + i];
      sum += r * r;
    }
    s[c] = sum;
  }
  return s;
}

std::vector<Eigen::VectorXd> ModelProblem::sse(const std::vector<Eigen::VectorXd>& xs) const {
  std::vector<Eigen::VectorXd> out(xs.size());
  std::vector<Eigen::VectorXd> todo;
  std::vector<std::size_t> where;
  {
    std::lock_guard<std::mutex> lock(cache_mutex_);
    for (std::size_t i = 0; i < xs.size(); ++i) {
      const auto it = cache_.find(key_of(xs[i]));
      if (it != cache_.end()) {
        out[i] = it->second;
      } else {
        todo.push_back(xs[i]);
        where.push_back(i);
      }
    }
  }
  if (todo.empty()) return out;
  if (batch_sse_) {
    const auto f = run_sse(todo);
    for (std::size_t k = 0; k < todo.size(); ++k) out[where[k]] = f[k];
  } else {
    const auto f = predict(todo);
    for (std::size_t k = 0; k < todo.size(); ++k) out[where[k]] = sse_of(f[k]);
  }
  std::lock_guard<std::mutex> lock(cache_mutex_);
  if (cache_.size() + todo.size() > kCacheLimit) {
    // Full: start again from this call's points, hits included (a sampler asks for its chains'
    // states right after their proposals, and must find them).
    cache_.clear();
    for (std::size_t i = 0; i < xs.size(); ++i) cache_[key_of(xs[i])] = out[i];
  } else {
    for (std::size_t k = 0; k < todo.size(); ++k) cache_[key_of(todo[k])] = out[where[k]];
  }
  return out;
}

double ModelProblem::log_posterior(const Eigen::VectorXd& x, const Eigen::VectorXd& sse,
                                   const Eigen::VectorXd& noise_var) const {
  const double lp = log_prior(x);
  if (lp == kNegInf) return kNegInf;
  if (!sse.allFinite()) return kNaN;  // the run failed: the sampler counts it and rejects
  double ll = lp;
  for (int c = 0; c < num_channels(); ++c) {
    // The likelihood to the power 1 / tau; the Jeffreys prior on s^2 contributes -log s^2.
    ll += (-0.5 * sse[c] / noise_var[c]) / tau_[c] - (0.5 * effective_rows(c) + 1.0) * std::log(noise_var[c]);
  }
  return ll;
}

Target ModelProblem::target() const {
  Target t;
  t.dim = dim();
  t.nuisance_dim = num_channels();
  t.lower.resize(dim());
  t.upper.resize(dim());
  for (int j = 0; j < dim(); ++j) {
    t.lower[j] = parameters_[j].prior.lower;
    t.upper[j] = parameters_[j].prior.upper;
  }
  t.log_density = [this](const Eigen::VectorXd& x, const Eigen::VectorXd& nv) {
    if (!std::isfinite(log_prior(x))) return kNegInf;
    return log_posterior(x, sse({x})[0], nv);
  };
  t.log_density_batch = [this](const std::vector<Eigen::VectorXd>& xs, const std::vector<Eigen::VectorXd>& nvs,
                               std::vector<double>& out) {
    const auto s = sse(xs);
    out.resize(xs.size());
    for (std::size_t i = 0; i < xs.size(); ++i)
      out[i] = std::isfinite(log_prior(xs[i])) ? log_posterior(xs[i], s[i], nvs[i]) : kNegInf;
  };
  // With the Jeffreys prior 1/s^2, integrating s_c^2 out of N(y | f, s_c^2)^(1/tau_c) leaves
  // SSE_c^(-N_c / (2 tau_c)).
  t.log_marginal_batch = [this](const std::vector<Eigen::VectorXd>& xs, std::vector<double>& out) {
    const auto s = sse(xs);
    out.resize(xs.size());
    for (std::size_t i = 0; i < xs.size(); ++i) {
      out[i] = log_prior(xs[i]);
      if (!std::isfinite(out[i])) continue;
      for (int c = 0; c < num_channels(); ++c)
        out[i] -= 0.5 * effective_rows(c) * std::log(s[i][c]);
    }
  };
  t.gibbs = [this](const Eigen::VectorXd& x, Eigen::VectorXd& nv, Rng& rng) {
    const Eigen::VectorXd s = sse({x})[0];
    for (int c = 0; c < num_channels(); ++c)  // s^2 | theta ~ InvGamma(N/(2 tau), SSE/(2 tau))
      nv[c] = 0.5 * s[c] / tau_[c] / rng.gamma(0.5 * effective_rows(c));
  };
  return t;
}

}  // namespace terracal::bayes
