#pragma once
// The bevameter rigs' options, shared by `bevameter` and `pipeline` so that both name, document,
// default and check them alike: the plates (sizes, stroke, speed, CRM spacing and bin) and the
// annulus (radii, loads, turn, settling, load ramp, CRM step).
#include <string>

#include "apps/cli_fwd.hpp"

#include "apps/rig_runs.hpp"

namespace terracal::app {

// The options that are comma lists: read as text, parsed once CLI11 is done.
struct BevameterLists {
  std::string plates = "0.2,0.3", annulus = "0.15,0.20", shear_loads;
};

// Binds --plates, --max-sinkage, --plate-speed, --plate-spacing, --plate-wall-radii,
// --plate-depth-scale, --annulus, --shear-loads, --shear-angle, --shear-rate, --shear-settle,
// --shear-load-ramp and --shear-step (defaults: the values in `plan` and `lists`).
void add_bevameter_options(CLI::App* sub, BevameterPlan& plan, BevameterLists& lists);

// The lists into `plan`: plate radii, INNER,OUTER annulus radii, normal loads; InputError naming the
// option for text that is no list of numbers (their ranges: BevameterRanges, check_bevameter).
void apply_bevameter_lists(const BevameterLists& lists, BevameterPlan& plan);

}  // namespace terracal::app
