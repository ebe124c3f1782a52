#pragma once
// Soils and sites for the SCM tests.
#include "lowfi/scm_soil.hpp"
#include "lowfi/scm_terrain.hpp"

namespace terracal::test {

// Dry sand (Land Locomotion Lab), Wong's Table 2.3 (shared/reference/bekker_wong_soils.csv); Wong gives
// no Janosi k for it, k = 0.025 m is a typical value for loose sand.
inline lowfi::ScmSoil scm_dry_sand() {
  lowfi::ScmSoil s;
  s.n = 1.1;
  s.Kc = 990;
  s.Kphi = 1528430;
  s.cohesion = 1040;
  s.friction_deg = 28;
  s.janosi_k = 0.025;
  return s;
}

inline lowfi::ScmSite scm_site(const lowfi::ScmSoil& soil, double grid, double dt, std::vector<std::string> effects = {}) {
  lowfi::ScmSettings s;
  s.grid = grid;
  s.time_step = dt;
  s.effects = lowfi::parse_scm_effects(effects, "effects");
  return lowfi::ScmSite(soil, s);
}

}  // namespace terracal::test
