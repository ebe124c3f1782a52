#pragma once
// Reads --soil / --scm into a SoilChoice for the chosen solver; InputError when the wrong file or
// both or neither are given.
#include <string>
#include <vector>

#include "apps/rig_runs.hpp"

namespace terracal::app {

SoilChoice choose_soil(SoilModel solver, const TerrainOptions& o);

}  // namespace terracal::app
