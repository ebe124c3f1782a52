#pragma once
// A ParaView snapshot (.vtu) of an SCM terrain's disturbed surface: every stored node at its present
// height (the undisturbed level, less its plastic sinkage, plus what bulldozing piled on it), joined
// into quads where four neighbouring nodes are stored; point data: the plastic sinkage (m), the last
// normal pressure and shear stress (Pa). Undisturbed soil is not stored and not drawn.
#include <filesystem>

#include "lowfi/scm_terrain.hpp"

namespace terracal::lowfi {

// Returns the number of nodes written.
std::size_t write_scm_surface_vtu(const std::filesystem::path& file, const ScmTerrain& terrain, double time);

}  // namespace terracal::lowfi
