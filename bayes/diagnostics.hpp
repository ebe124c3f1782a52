#pragma once
// MCMC convergence diagnostics of Vehtari, Gelman, Simpson, Carpenter & Bürkner (2021),
// "Rank-normalization, folding, and localization: an improved R-hat", Bayesian Analysis 16(2),
// computed as Stan / ArviZ / the R package `posterior` compute them, so that numbers in our
// summary table mean what users of those tools expect.
//
// Input: chains[c][i] = draw i of chain c. All chains must have the same length >= 2 and finite
// draws (std::invalid_argument otherwise). Chains of >= 4 draws are split in halves (the middle
// draw of an odd length is dropped); shorter chains are used whole, since a half of one draw has
// no variance. A single chain of fewer than 4 draws has nothing to compare and throws.
// Constant input gives R-hat = 1 and ESS = number of draws, never NaN.
#include <vector>

namespace terracal::bayes {

using Chains = std::vector<std::vector<double>>;

double rhat_split(const Chains& chains);  // classic split R-hat (Gelman et al., BDA3)
double rhat_rank(const Chains& chains);   // max(bulk, tail) rank-normalised split R-hat
double ess_basic(const Chains& chains);   // split-chain ESS, Geyer initial monotone sequence
double ess_bulk(const Chains& chains);    // ess_basic of the rank-normalised draws
double ess_tail(const Chains& chains);    // min ESS of the indicators x <= q05 and x <= q95

struct VariableSummary {
  double mean, sd, q05, q50, q95, rhat, ess_bulk, ess_tail;
};
VariableSummary summarize(const Chains& chains);

// acov[t] = (1/n) sum_{i < n-t} (x_i - mean)(x_{i+t} - mean), t = 0..n-1, by FFT in O(n log n):
// the O(n^2) sum is too slow for the 10^5-draw chains of a long calibration run.
std::vector<double> autocovariance(const std::vector<double>& x);

// Quantile of linearly interpolated order statistics (R type 7, numpy's default).
double quantile(std::vector<double> draws, double p);

}  // namespace terracal::bayes
