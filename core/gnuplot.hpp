#pragma once
// Running gnuplot as an external program. Plots are optional output: callers check
// gnuplot_available() (or catch RunError) and warn instead of failing a calibration.
#include <string>

namespace terracal {

// True when an executable `gnuplot` is found in one of the PATH folders. Looked up once per
// process: PATH does not change while terracal runs.
bool gnuplot_available();

// Writes `script` to `workdir/plot.gp` and runs `gnuplot plot.gp` with `workdir` as the current
// folder (relative data-file names in the script resolve there). Throws RunError carrying
// gnuplot's error output when gnuplot is missing, cannot start, or exits with a non-zero status.
void run_gnuplot(const std::string& script, const std::string& workdir);

}  // namespace terracal
