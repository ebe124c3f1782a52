#pragma once
// Soils and sites for the SCM tests.
#include <string>

#include "core/csv.hpp"
#include "core/errors.hpp"
#include "lowfi/scm_soil.hpp"
#include "lowfi/scm_terrain.hpp"
#include "tests/test_paths.hpp"

namespace terracal::test {

inline lowfi::ScmSoil scm_dry_sand() { return lowfi::reference_dry_sand(); }

// The Bekker and Mohr columns of a row of shared/reference's tables (bekker_wong_soils.csv and
// chrono_scm_presets.csv name them alike); the caller sets k, Ke and the damping.
inline lowfi::ScmSoil scm_soil_of_row(const CsvTable& t, std::size_t i) {
  lowfi::ScmSoil s;
  s.n = t.number(i, "n");
  s.Kc = t.number(i, "Kc");
  s.Kphi = t.number(i, "Kphi");
  s.cohesion = t.number(i, "cohesion_Pa");
  s.friction_deg = t.number(i, "friction_deg");
  return s;
}

inline CsvTable wong_soils() { return CsvTable::read(terracal::test::reference_dir() + "/bekker_wong_soils.csv"); }

// LETE sand of Wong's table, with its Janosi k, and Chrono's default elastic stiffness and damping:
// stiff enough that the 108 kg wheel sinks only 3 mm, a third of it elastic.
inline lowfi::ScmSoil scm_lete_sand() {
  const CsvTable t = wong_soils();
  for (std::size_t i = 0; i < t.rows(); ++i)
    if (t.text(i, "soil") == "LETE sand") {
      lowfi::ScmSoil s = scm_soil_of_row(t, i);
      s.janosi_k = t.number(i, "janosi_k_m");
      return s;
    }
  throw InputError("bekker_wong_soils.csv: no row 'LETE sand'");
}

inline lowfi::ScmSite scm_site(const lowfi::ScmSoil& soil, double grid, double dt,
                               std::vector<std::string> effects = {}) {
  lowfi::ScmSettings s;
  s.grid = grid;
  s.time_step = dt;
  s.effects = lowfi::parse_scm_effects(effects, "effects");
  return lowfi::ScmSite(soil, s);
}

}  // namespace terracal::test
