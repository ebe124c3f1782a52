#include "apps/soil_choice.hpp"

#include <fmt/format.h>

#include "core/errors.hpp"

namespace terracal::app {

SoilChoice choose_soil(const std::string& solver, const TerrainOptions& o) {
  SoilChoice c;
  c.solver = solver;
  if (o.soil_json.empty() == o.scm_json.empty())
    throw InputError("give exactly one of --soil SOIL.json (a CRM material) or --scm SCM.json (an SCM parameter set)");
  if (solver == "crm") {
    if (o.soil_json.empty()) throw InputError("--solver/--terrain crm needs --soil SOIL.json (a CRM material), not --scm");
    c.crm = load_crm_soil(o.soil_json);
    c.gravity = c.crm->gravity;
  } else if (solver == "scm" || solver == "wong-reece") {
    if (o.scm_json.empty()) throw InputError(fmt::format("--solver/--terrain {} needs --scm SCM.json (an SCM parameter set), not --soil", solver));
    c.scm = load_scm_soil(o.scm_json);
    if (o.gravity.size() == 3) c.gravity = {o.gravity[0], o.gravity[1], o.gravity[2]};
  } else {
    throw InputError(fmt::format("solver '{}': expected crm, scm or wong-reece", solver));
  }
  return c;
}

}  // namespace terracal::app
