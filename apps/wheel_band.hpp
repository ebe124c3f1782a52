#pragma once
// The SCM wheel's posterior band: a calibration's posterior sets run through the steady SCM wheel
// (lowfi/scm_steady_wheel.hpp) at every slip of a sweep, 5/50/95 % per channel, and a few of them
// checked against the time-stepping SCM wheel. The pipeline's wheel plot draws it, its report tables it.
#include <array>
#include <string>
#include <vector>

#include "apps/rig_runs.hpp"
#include "lowfi/scm_soil.hpp"

namespace terracal::app {

struct WheelBand {
  std::vector<double> slips;
  // Per channel (drawbar pull [N], torque [N m], sinkage [m]) and slip: 5 %, 50 %, 95 %.
  std::array<std::vector<double>, 3> q05, q50, q95;
  int sets = 0, failed = 0;  // posterior sets run; those the steady wheel could not carry
  // Sets checked against the time-stepping wheel at check_slip: steady and time-stepped values.
  double check_slip = 0;
  std::vector<std::array<double, 3>> check_steady, check_stepped;
};

// The band of `sets` at `slips` for `wheel` under `gravity` [m/s^2]; slip_sinkage as the SCM wheel
// runs; `checks` sets (evenly spread over `sets`) rerun time-stepping (`scm_options`, `run`) at the
// sweep's middle slip.
WheelBand scm_wheel_band(const std::vector<lowfi::ScmSoil>& sets, const rigs::WheelSpec& wheel, const Vec3<double>& gravity,
                         const std::vector<double>& slips, bool slip_sinkage, const TerrainOptions& scm_options,
                         const rigs::WheelRun& run, int checks = 3);

// band.csv (slip, then q05/q50/q95 of dbp_N, torque_Nm, sinkage_m) and back, for --replot.
void write_wheel_band_csv(const std::string& path, const WheelBand& band);
WheelBand read_wheel_band_csv(const std::string& path);

}  // namespace terracal::app
