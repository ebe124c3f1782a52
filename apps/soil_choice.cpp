#include "apps/soil_choice.hpp"

#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "core/errors.hpp"

namespace terracal::app {

void check_rig_gravity(const Vec3<double>& g, const std::string& source) {
  const double size = norm(g);
  if (!std::isfinite(size) || !(g.z < 0) || size > 1000)
    throw InputError(
        fmt::format("{} [{}, {}, {}] m/s^2: expected gravity pointing down (g_z < 0) with |g| <= 1000 "
                    "m/s^2, such as [0, 0, -9.81]: the rigs load their bodies by weight",
                    source, g.x, g.y, g.z));
  if (std::hypot(g.x, g.y) > 0.01 * size)
    spdlog::warn("{} [{}, {}, {}] m/s^2 is not vertical: the rigs' loads and the soil's weight lean by {:.3g} deg",
                 source, g.x, g.y, g.z, std::atan2(std::hypot(g.x, g.y), -g.z) * 180 / M_PI);
}

namespace {
// Options of the other solver are refused rather than ignored: a --spacing given to an SCM run would
// otherwise look as if it had set the resolution.
void refuse_other_solvers_options(SoilModel solver, const TerrainOptions& o) {
  const auto refuse = [&](const std::vector<std::string>& given, const char* whose) {
    if (!given.empty())
      throw InputError(fmt::format("{}: {} only; --solver/--terrain {} does not read {}", fmt::join(given, ", "), whose,
                                   soil_model_name(solver), given.size() == 1 ? "it" : "them"));
  };
  if (solver != SoilModel::kCrm) refuse(o.crm_given, "for CRM");
  if (solver != SoilModel::kScm) refuse(o.scm_given, "for SCM");
}
}  // namespace

SoilChoice choose_soil(SoilModel solver, const TerrainOptions& o) {
  refuse_other_solvers_options(solver, o);
  SoilChoice c;
  c.solver = solver;
  if (o.soil_json.empty() == o.scm_json.empty())
    throw InputError("give exactly one of --soil SOIL.json (a CRM material) or --scm SCM.json (an SCM parameter set)");
  if (solver == SoilModel::kCrm) {
    if (o.soil_json.empty())
      throw InputError("--solver/--terrain crm needs --soil SOIL.json (a CRM material), not --scm");
    if (!o.gravity.empty())
      throw InputError("--gravity: only for SCM and Wong-Reece; a CRM soil's gravity is the key 'gravity' of --soil");
    c.crm = load_crm_soil(o.soil_json);
    c.gravity = c.crm->gravity;
    check_rig_gravity(c.gravity, o.soil_json + ": key 'soil.gravity'");
  } else {
    if (o.scm_json.empty())
      throw InputError(fmt::format("--solver/--terrain {} needs --scm SCM.json (an SCM parameter set), not --soil",
                                   soil_model_name(solver)));
    c.scm = load_scm_soil(o.scm_json);
    if (o.gravity.size() == 3) c.gravity = {o.gravity[0], o.gravity[1], o.gravity[2]};
    check_rig_gravity(c.gravity, o.gravity.empty() ? "gravity" : "--gravity");
  }
  return c;
}

}  // namespace terracal::app
