#include "apps/soil_choice.hpp"

#include <fmt/format.h>

#include "core/errors.hpp"

namespace terracal::app {

SoilChoice choose_soil(SoilModel solver, const TerrainOptions& o) {
  SoilChoice c;
  c.solver = solver;
  if (o.soil_json.empty() == o.scm_json.empty())
    throw InputError("give exactly one of --soil SOIL.json (a CRM material) or --scm SCM.json (an SCM parameter set)");
  if (solver == SoilModel::kCrm) {
    if (o.soil_json.empty())
      throw InputError("--solver/--terrain crm needs --soil SOIL.json (a CRM material), not --scm");
    c.crm = load_crm_soil(o.soil_json);
    c.gravity = c.crm->gravity;
  } else {
    if (o.scm_json.empty())
      throw InputError(fmt::format("--solver/--terrain {} needs --scm SCM.json (an SCM parameter set), not --soil",
                                   soil_model_name(solver)));
    c.scm = load_scm_soil(o.scm_json);
    if (o.gravity.size() == 3) c.gravity = {o.gravity[0], o.gravity[1], o.gravity[2]};
  }
  return c;
}

}  // namespace terracal::app
