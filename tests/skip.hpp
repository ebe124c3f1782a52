#pragma once
// A test that cannot run on this machine (no CUDA device, no gnuplot) ends at once with one line
// that starts "SKIPPED:". CTest reports such a test as skipped (CMakeLists.txt sets
// SKIP_REGULAR_EXPRESSION on every test) and Catch2 prints the line as a warning: a skip is always
// visible, never a silent pass.
#include <catch2/catch.hpp>

#include <cstdio>
#include <string>

#include "core/device_selftest.hpp"
#include "core/gnuplot.hpp"

namespace terracal::test {

inline void report_skip(const std::string& test, const std::string& why) {
  std::printf("SKIPPED: %s: %s\n", test.c_str(), why.c_str());
  std::fflush(stdout);
  WARN("SKIPPED: " << test << ": " << why);
}

// True where a CUDA device is present; elsewhere reports the skip of `test`.
inline bool cuda_device_or_skip(const std::string& test) {
  const CudaDeviceInfo info = cuda_device_info();
  if (!info.available) report_skip(test, "no CUDA device (" + info.description + ")");
  return info.available;
}

// True where gnuplot is on the PATH; elsewhere reports the skip of `test`.
inline bool gnuplot_or_skip(const std::string& test) {
  const bool found = gnuplot_available();
  if (!found) report_skip(test, "gnuplot not found on the PATH");
  return found;
}

}  // namespace terracal::test
