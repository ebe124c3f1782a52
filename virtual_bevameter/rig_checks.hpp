#pragma once
// Checks shared by the rigs: a value in its range (InputError naming it), and a body that fits the
// site with room to move.
#include <string>

#include "core/terrain.hpp"

namespace terracal::rigs {

void check_range(const std::string& key, double value, double lo, double hi, const std::string& unit);
// Throws InputError when a body reaching reach_x, reach_y from its (x, y) (and travelling travel_x
// beyond) would come closer than one reach to the site's walls: such a test would measure the bin.
void check_fits(const TerrainSite& site, const RigidBody& body, double reach_x, double reach_y, double travel_x = 0);

}  // namespace terracal::rigs
