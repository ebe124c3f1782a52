#pragma once
// Soils and sites for the SCM tests.
#include "lowfi/scm_soil.hpp"
#include "lowfi/scm_terrain.hpp"

namespace terracal::test {

inline lowfi::ScmSoil scm_dry_sand() { return lowfi::reference_dry_sand(); }

// LETE sand (shared/reference/bekker_wong_soils.csv: Wong's values, with its Janosi k), with Chrono's
// default elastic stiffness and damping: stiff enough that the 108 kg wheel sinks only 3 mm, a third
// of it elastic.
inline lowfi::ScmSoil scm_lete_sand() {
  lowfi::ScmSoil s;
  s.n = 0.79;
  s.Kc = 102000;
  s.Kphi = 5301000;
  s.cohesion = 1300;
  s.friction_deg = 31.1;
  s.janosi_k = 0.012;
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
