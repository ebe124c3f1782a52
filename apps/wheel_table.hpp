#pragma once
// `terracal wheel-table`'s grid: the single-wheel rig on one soil over loads x slips x slip angles,
// the runs spread over the CPU's threads, gathered into the table the ROMs' deformable_terrain
// effect reads (rom/terrain_table_h5.hpp).
#include <vector>

#include "apps/rig_runs.hpp"
#include "rom/terrain_table_h5.hpp"

namespace terracal::app {

struct WheelTablePlan {
  std::vector<double> loads;   // [N] on the wheel
  std::vector<double> slips;   // longitudinal slips
  std::vector<double> angles{0};  // slip angles [rad], from 0
  rigs::WheelRun run;          // duration and averaging of each rig run (its slip_angle is set per run)
};

// Checks the plan (InputError naming the option) before any run.
void check_wheel_table(const SoilChoice& soil, const TerrainOptions& o, const rigs::WheelSpec& wheel,
                       const WheelTablePlan& plan);
// Every grid point's steady means; `soil` and `wheel` name the inputs in the table.
rom::TerrainTable run_wheel_table(const SoilChoice& soil, const TerrainOptions& o, const rigs::WheelSpec& wheel,
                                  const WheelTablePlan& plan);

}  // namespace terracal::app
