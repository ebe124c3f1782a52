#include "virtual_bevameter/curve_change.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include <fmt/format.h>

#include "core/errors.hpp"

namespace terracal::rigs {

namespace {

void check_curve(const Curve& c, const char* which) {
  if (c.x.size() != c.y.size())
    throw InputError(fmt::format("curve_change: {} curve has {} x and {} y samples", which, c.x.size(), c.y.size()));
  for (std::size_t i = 1; i < c.x.size(); ++i)
    if (!(c.x[i] >= c.x[i - 1]))
      throw InputError(
          fmt::format("curve_change: {} curve's x falls at sample {} ({} after {})", which, i, c.x[i], c.x[i - 1]));
}

// c.y at x, for x within [c.x.front(), c.x.back()].
double interpolate(const Curve& c, double x) {
  const auto hi = std::size_t(std::lower_bound(c.x.begin(), c.x.end(), x) - c.x.begin());
  if (hi == 0) return c.y.front();
  const double span = c.x[hi] - c.x[hi - 1];
  const double w = span > 0 ? (x - c.x[hi - 1]) / span : 1.0;
  return c.y[hi - 1] + w * (c.y[hi] - c.y[hi - 1]);
}

}  // namespace

double curve_change(const Curve& base, const Curve& check) {
  check_curve(base, "base");
  check_curve(check, "check");
  if (check.x.empty()) return 0;
  std::vector<double> a, b;  // the two curves at the base's x within the common range
  for (std::size_t i = 0; i < base.x.size(); ++i) {
    if (base.x[i] < check.x.front() || base.x[i] > check.x.back()) continue;
    a.push_back(base.y[i]);
    b.push_back(interpolate(check, base.x[i]));
  }
  constexpr std::size_t kParts = 5;
  const std::size_t n = a.size();
  if (n < kParts) return 0;
  double diff = 0, scale = 0;
  for (std::size_t p = 0; p < kParts; ++p) {
    const std::size_t lo = p * n / kParts, hi = (p + 1) * n / kParts;
    double ma = 0, mb = 0;
    for (std::size_t i = lo; i < hi; ++i) ma += a[i], mb += b[i];
    ma /= double(hi - lo), mb /= double(hi - lo);
    diff = std::max(diff, std::abs(ma - mb));
    scale = std::max({scale, std::abs(ma), std::abs(mb)});
  }
  return scale > 0 ? diff / scale : 0;
}

Curve mean_curve(const std::vector<Curve>& realisations) {
  if (realisations.empty()) throw InputError("mean_curve: no curves");
  for (const Curve& c : realisations) check_curve(c, "realisation");
  Curve mean;
  const Curve& first = realisations.front();
  for (std::size_t i = 0; i < first.x.size(); ++i) {
    const double x = first.x[i];
    double sum = 0;
    bool covered = true;
    for (const Curve& c : realisations) {
      if (c.x.empty() || x < c.x.front() || x > c.x.back()) {
        covered = false;
        break;
      }
      sum += interpolate(c, x);
    }
    if (!covered) continue;
    mean.x.push_back(x);
    mean.y.push_back(sum / double(realisations.size()));
  }
  return mean;
}

double realisation_scatter(const std::vector<Curve>& realisations) {
  double largest = 0;
  for (std::size_t a = 0; a < realisations.size(); ++a)
    for (std::size_t b = a + 1; b < realisations.size(); ++b)
      largest = std::max(largest, curve_change(realisations[a], realisations[b]));
  return largest;
}

}  // namespace terracal::rigs
