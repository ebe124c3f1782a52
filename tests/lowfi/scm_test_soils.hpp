#pragma once
// Soils and sites for the SCM tests.
#include "lowfi/scm_soil.hpp"
#include "lowfi/scm_terrain.hpp"

namespace terracal::test {

inline lowfi::ScmSoil scm_dry_sand() { return lowfi::reference_dry_sand(); }

inline lowfi::ScmSite scm_site(const lowfi::ScmSoil& soil, double grid, double dt, std::vector<std::string> effects = {}) {
  lowfi::ScmSettings s;
  s.grid = grid;
  s.time_step = dt;
  s.effects = lowfi::parse_scm_effects(effects, "effects");
  return lowfi::ScmSite(soil, s);
}

}  // namespace terracal::test
