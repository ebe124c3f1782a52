#pragma once
// Checks shared by the rigs: a value in its range (InputError naming it), and a body that fits the
// site with room to move.
#include <string>

#include "core/terrain.hpp"

namespace terracal::rigs {

void check_range(const std::string& key, double value, double lo, double hi, const std::string& unit);
// Throws InputError when a body reaching `reach` from its (x, y) would come closer than one reach to
// the site's walls: such a test would measure the bin, not the soil.
void check_fits(const TerrainSite& site, const RigidBody& body, double reach, double travel_x = 0);

}  // namespace terracal::rigs
