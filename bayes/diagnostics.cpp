#include "bayes/diagnostics.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <stdexcept>

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_fft_halfcomplex.h>
#include <gsl/gsl_fft_real.h>

namespace terracal::bayes {
namespace {

void check_chains(const Chains& chains) {
  if (chains.empty()) throw std::invalid_argument("diagnostics: no chains");
  const std::size_t n = chains.front().size();
  if (n < 2) throw std::invalid_argument("diagnostics: each chain needs at least 2 draws");
  for (const auto& c : chains) {
    if (c.size() != n) throw std::invalid_argument("diagnostics: chains have different lengths");
    // NaN would break the sorts behind ranks and quantiles; a sampler never stores one.
    for (double v : c)
      if (!std::isfinite(v)) throw std::invalid_argument("diagnostics: draws must be finite");
  }
}

std::size_t total_draws(const Chains& chains) { return chains.size() * chains.front().size(); }

std::vector<double> pooled(const Chains& chains) {
  std::vector<double> all;
  all.reserve(total_draws(chains));
  for (const auto& c : chains) all.insert(all.end(), c.begin(), c.end());
  return all;
}

// Exact equality: a chain stuck at one value repeats it exactly, and a scale-free test matters
// because parameters range from 1e-2 to 1e6.
bool is_constant(const Chains& chains) {
  const double first = chains.front().front();
  for (const auto& c : chains)
    for (double v : c)
      if (v != first) return false;
  return true;
}

// Halves detect a trend within a chain that whole chains would average out.
Chains split_chains(const Chains& chains) {
  const std::size_t n = chains.front().size();
  if (n < 4) {
    if (chains.size() < 2) throw std::invalid_argument("diagnostics: a single chain needs at least 4 draws");
    return chains;
  }
  const std::size_t half = n / 2;
  Chains out;
  for (const auto& c : chains) {
    out.emplace_back(c.begin(), c.begin() + half);
    out.emplace_back(c.end() - half, c.end());
  }
  return out;
}

double mean_of(const std::vector<double>& x) { return std::accumulate(x.begin(), x.end(), 0.0) / double(x.size()); }

double variance_of(const std::vector<double>& x) {  // unbiased (ddof = 1)
  const double m = mean_of(x);
  double s = 0;
  for (double v : x) s += (v - m) * (v - m);
  return s / double(x.size() - 1);
}

// Average ranks (1-based) of all draws pooled; ties share their mean rank.
std::vector<double> average_ranks(const std::vector<double>& x) {
  std::vector<std::size_t> order(x.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return x[a] < x[b]; });
  std::vector<double> rank(x.size());
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i;
    while (j + 1 < order.size() && x[order[j + 1]] == x[order[i]]) ++j;
    const double r = 0.5 * double(i + j) + 1.0;
    for (std::size_t k = i; k <= j; ++k) rank[order[k]] = r;
    i = j + 1;
  }
  return rank;
}

// Normal scores of the pooled ranks, z = Phi^-1((r - 3/8) / (S + 1/4)) (Blom), same shape:
// makes R-hat and ESS well defined for heavy tails and invariant to monotone transforms.
Chains rank_normalise(const Chains& chains) {
  const std::vector<double> rank = average_ranks(pooled(chains));
  const double s = double(rank.size());
  Chains z = chains;
  std::size_t k = 0;
  for (auto& c : z)
    for (double& v : c) v = gsl_cdf_ugaussian_Pinv((rank[k++] - 0.375) / (s + 0.25));
  return z;
}

// |x - median|: the bulk R-hat misses chains that differ in spread only; folding turns that
// into a difference in location.
Chains fold(const Chains& chains) {
  const double med = quantile(pooled(chains), 0.5);
  Chains f = chains;
  for (auto& c : f)
    for (double& v : c) v = std::abs(v - med);
  return f;
}

// R-hat of chains as given (already split): sqrt(var+ / W), var+ = (n-1)/n W + B/n.
double rhat_of(const Chains& chains) {
  if (is_constant(chains)) return 1.0;
  const double n = double(chains.front().size());
  std::vector<double> means, vars;
  for (const auto& c : chains) {
    means.push_back(mean_of(c));
    vars.push_back(variance_of(c));
  }
  const double b = n * variance_of(means);
  const double w = mean_of(vars);
  return std::sqrt((b / w + n - 1.0) / n);
}

// Mean over chains of the autocovariance at each lag.
std::vector<double> mean_autocovariance(const Chains& chains) {
  std::vector<double> acov(chains.front().size(), 0.0);
  for (const auto& c : chains) {
    const std::vector<double> a = autocovariance(c);
    for (std::size_t t = 0; t < a.size(); ++t) acov[t] += a[t] / double(chains.size());
  }
  return acov;
}

// Geyer's initial positive sequence then initial monotone sequence on the multi-chain
// autocorrelations rho_t = 1 - (W - mean acov_t) / var+ (Stan reference manual, "Effective
// sample size"); line for line the algorithm of Stan / ArviZ so that our numbers match theirs.
double ess_of(const Chains& chains) {
  const long m = long(chains.size()), n = long(chains.front().size());
  const std::vector<double> acov = mean_autocovariance(chains);
  std::vector<double> means;
  for (const auto& c : chains) means.push_back(mean_of(c));
  const double mean_var = acov[0] * double(n) / double(n - 1);  // W
  double var_plus = mean_var * double(n - 1) / double(n);
  if (m > 1) var_plus += variance_of(means);
  auto rho = [&](long t) { return 1.0 - (mean_var - acov[t]) / var_plus; };

  std::vector<double> rho_hat(n, 0.0);
  double even = 1.0, odd = rho(1);
  rho_hat[0] = even;
  rho_hat[1] = odd;
  long t = 1;
  while (t < n - 3 && even + odd > 0.0) {  // initial positive sequence
    even = rho(t + 1);
    odd = rho(t + 2);
    if (even + odd >= 0.0) {
      rho_hat[t + 1] = even;
      rho_hat[t + 2] = odd;
    }
    t += 2;
  }
  const long max_t = t - 2;
  if (even > 0.0) rho_hat[max_t + 1] = even;  // the last positive even lag still carries information
  for (t = 1; t <= max_t - 2; t += 2) {       // initial monotone sequence
    if (rho_hat[t + 1] + rho_hat[t + 2] > rho_hat[t - 1] + rho_hat[t]) {
      rho_hat[t + 1] = 0.5 * (rho_hat[t - 1] + rho_hat[t]);
      rho_hat[t + 2] = rho_hat[t + 1];
    }
  }
  double tau = -1.0 + rho_hat[max_t + 1];
  for (long k = 0; k <= max_t; ++k) tau += 2.0 * rho_hat[k];
  const double draws = double(m * n);
  tau = std::max(tau, 1.0 / std::log10(draws));  // caps ESS at draws*log10(draws), as Stan does
  return draws / tau;
}

}  // namespace

std::vector<double> autocovariance(const std::vector<double>& x) {
  const std::size_t n = x.size();
  std::size_t size = 1;
  while (size < 2 * n) size *= 2;  // zero padding to >= 2n turns the circular correlation linear
  const double m = mean_of(x);
  std::vector<double> data(size, 0.0);
  for (std::size_t i = 0; i < n; ++i) data[i] = x[i] - m;
  gsl_fft_real_radix2_transform(data.data(), 1, size);
  // Half-complex layout: data[k] = Re_k (k <= size/2), data[size-k] = Im_k. Replace by |X_k|^2.
  data[0] *= data[0];
  data[size / 2] *= data[size / 2];
  for (std::size_t k = 1; k < size / 2; ++k) {
    data[k] = data[k] * data[k] + data[size - k] * data[size - k];
    data[size - k] = 0.0;
  }
  gsl_fft_halfcomplex_radix2_inverse(data.data(), 1, size);  // includes the 1/size factor
  data.resize(n);
  for (double& v : data) v /= double(n);
  return data;
}

double quantile(std::vector<double> draws, double p) {
  if (draws.empty()) throw std::invalid_argument("quantile: no draws");
  const double h = p * double(draws.size() - 1);
  const auto lo = static_cast<std::ptrdiff_t>(std::floor(h));
  // Two order statistics in O(n), not a full sort: summaries of 10^5-draw chains call this often.
  std::nth_element(draws.begin(), draws.begin() + lo, draws.end());
  const double below = draws[lo];
  if (lo + 1 >= std::ptrdiff_t(draws.size())) return below;
  const double above = *std::min_element(draws.begin() + lo + 1, draws.end());
  return below + (h - double(lo)) * (above - below);
}

double rhat_split(const Chains& chains) {
  check_chains(chains);
  return rhat_of(split_chains(chains));
}

double rhat_rank(const Chains& chains) {
  check_chains(chains);
  const Chains split = split_chains(chains);
  return std::max(rhat_of(rank_normalise(split)), rhat_of(rank_normalise(fold(split))));
}

double ess_basic(const Chains& chains) {
  check_chains(chains);
  if (is_constant(chains)) return double(total_draws(chains));
  return ess_of(split_chains(chains));
}

double ess_bulk(const Chains& chains) {
  check_chains(chains);
  if (is_constant(chains)) return double(total_draws(chains));
  return ess_of(rank_normalise(split_chains(chains)));
}

double ess_tail(const Chains& chains) {
  check_chains(chains);
  const std::vector<double> all = pooled(chains);
  double ess = std::numeric_limits<double>::infinity();  // ESS may exceed the draw count
  for (double p : {0.05, 0.95}) {
    const double q = quantile(all, p);
    Chains indicator = chains;
    for (auto& c : indicator)
      for (double& v : c) v = v <= q ? 1.0 : 0.0;
    ess = std::min(ess, ess_basic(indicator));
  }
  return ess;
}

VariableSummary summarize(const Chains& chains) {
  check_chains(chains);
  const std::vector<double> all = pooled(chains);
  VariableSummary s{};
  s.mean = mean_of(all);
  s.sd = std::sqrt(variance_of(all));
  s.q05 = quantile(all, 0.05);
  s.q50 = quantile(all, 0.5);
  s.q95 = quantile(all, 0.95);
  s.rhat = rhat_rank(chains);
  s.ess_bulk = ess_bulk(chains);
  s.ess_tail = ess_tail(chains);
  return s;
}

}  // namespace terracal::bayes
