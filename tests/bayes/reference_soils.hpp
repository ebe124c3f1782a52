#pragma once
// The Bekker-Wong-Janosi soils of the shared reference table, as parameter vectors for tests.
#include <string>
#include <vector>

#include "bayes/scm_parameters.hpp"
#include "core/csv.hpp"
#include "tests/test_paths.hpp"

namespace terracal::test {

struct ReferenceSoil {
  std::string name;
  bayes::ParamVector truth;
};

// k = 0.01 m where the table leaves it empty.
inline std::vector<ReferenceSoil> reference_soils() {
  const auto t = CsvTable::read(terracal::test::reference_dir() + "/bekker_wong_soils.csv");
  std::vector<ReferenceSoil> soils;
  for (std::size_t i = 0; i < t.rows(); ++i) {
    ReferenceSoil s;
    s.name =
        t.text(i, "soil") + (t.text(i, "moisture_percent").empty() ? "" : " " + t.text(i, "moisture_percent") + " %");
    s.truth = {
        t.number(i, "Kc"),          t.number(i, "Kphi"),         t.number(i, "n"),
        t.number(i, "cohesion_Pa"), t.number(i, "friction_deg"), t.optional_number(i, "janosi_k_m").value_or(0.01)};
    soils.push_back(s);
  }
  return soils;
}

}  // namespace terracal::test
