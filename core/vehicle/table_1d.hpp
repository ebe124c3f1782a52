#pragma once
// A piecewise-linear table y(x) of fixed capacity (engine torque maps, torque-converter maps):
// a plain struct, so that it lives in a vehicle's parameters on the GPU as on the CPU. Outside its
// range the end values hold (as Chrono's interpolated maps do). Readers validate that x increases.
#include "core/host_device.hpp"

namespace terracal {

struct Table1d {
  static constexpr int kMaxPoints = 32;
  int n = 0;
  double x[kMaxPoints] = {};
  double y[kMaxPoints] = {};

  TERRACAL_HD double operator()(double at) const {
    if (n == 0) return 0.0;
    if (at <= x[0]) return y[0];
    if (at >= x[n - 1]) return y[n - 1];
    int i = 1;
    while (x[i] < at) ++i;  // tables are short: a linear scan beats bisection here
    const double t = (at - x[i - 1]) / (x[i] - x[i - 1]);
    return y[i - 1] + t * (y[i] - y[i - 1]);
  }
  TERRACAL_HD double x_max() const { return n > 0 ? x[n - 1] : 0.0; }
};

}  // namespace terracal
