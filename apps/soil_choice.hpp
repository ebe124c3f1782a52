#pragma once
// Reads --soil / --scm into a SoilChoice for the chosen solver; InputError when the wrong file or
// both or neither are given, or when its gravity cannot load a rig.
#include <string>
#include <vector>

#include "apps/rig_runs.hpp"

namespace terracal::app {

SoilChoice choose_soil(SoilModel solver, const TerrainOptions& o);

// The rigs load their bodies by weight (a wheel's mass, the annulus's dead loads): gravity must be
// finite, point down (g_z < 0) and stay within |g| <= 1000 m/s^2; InputError naming `source` (the
// soil file's key or --gravity) otherwise. A gravity with a horizontal part (a slope) is warned about.
void check_rig_gravity(const Vec3<double>& g, const std::string& source);

}  // namespace terracal::app
