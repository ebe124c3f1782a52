#pragma once
// How many rows of a curve count as one independent residual. A model that misses dense data by a
// smooth discrepancy leaves residuals that hardly change from one row to the next; counting them as
// independent makes the posterior as narrow as if the discrepancy were noise averaged away. An AR(1)
// process with lag-one correlation rho has the integrated correlation time tau = (1 + rho) / (1 - rho):
// N rows then carry about N / tau rows of information. The SCM calibration (--noise-correlation ar1)
// and the ROM calibration (--noise correlated) both temper their likelihoods by it.
#include <algorithm>
#include <cstddef>
#include <vector>

namespace terracal::bayes {

// tau from residuals r[i] in row order, with curve[i] the curve of row i (lags across two curves do
// not count); at least 1 and at most max(1, N / 10), so that a channel always keeps ten rows' weight.
inline double correlation_time(const std::vector<double>& r, const std::vector<int>& curve) {
  double lag0 = 0, lag1 = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    lag0 += r[i] * r[i];
    if (i + 1 < r.size() && curve[i + 1] == curve[i]) lag1 += r[i] * r[i + 1];
  }
  const double rho = lag0 > 0 ? std::clamp(lag1 / lag0, 0.0, 1.0) : 0.0;
  const double most = std::max(1.0, static_cast<double>(r.size()) / 10.0);
  return rho < 1 ? std::clamp((1 + rho) / (1 - rho), 1.0, most) : most;
}

}  // namespace terracal::bayes
