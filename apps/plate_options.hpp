#pragma once
// The plate rig's options, shared by `bevameter` and `pipeline` so that both name, document and
// default them alike: the plate's speed, its CRM spacing and its CRM bin (results/plate_bin_check).
#include <CLI/CLI.hpp>

#include "apps/rig_runs.hpp"

namespace terracal::app {

// Binds --plate-speed, --plate-spacing, --plate-wall-radii and --plate-depth-scale to `plan` (defaults: its values).
void add_plate_options(CLI::App* sub, BevameterPlan& plan);

}  // namespace terracal::app
