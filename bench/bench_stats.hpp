#pragma once
// Statistics shared by the benchmarks: every figure in RESULTS.md is a median of repeated runs.
#include <algorithm>
#include <vector>

namespace terracal::bench {

// The upper median (the middle element; for an even count the larger of the two middle ones).
inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace terracal::bench
