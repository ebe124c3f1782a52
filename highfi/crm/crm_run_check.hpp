#pragma once
// The health of a CRM run, checked as it goes: a run that goes bad stops at that step with the
// time, the place and what to try, rather than ending with a warning over a soil it lost. Shared by
// `terracal crm` (crm_run.cpp) and the rigs' CRM terrain (crm_terrain.cpp).
#include <optional>
#include <string>

#include "highfi/crm/crm_solver.hpp"

namespace terracal {

// Steps between two checks: a check is a reduction over every particle, a few percent of a step.
constexpr long kCrmCheckEvery = 10;

// Why a run was stopped.
struct CrmFailure {
  std::string kind;     // "non-finite", "lost", "too fast", "energy"
  std::string message;  // what happened, when and where, and what to try
};

class CrmRunCheck {
 public:
  // Takes the solver's state now as the reference (particles lost so far, mechanical energy, work).
  explicit CrmRunCheck(const CrmSolver& solver);

  // Checks the solver's state; an empty result when the run is sound. The criteria:
  // - any particle with a non-finite state;
  // - more than scene.checks.max_lost_fraction of the particles lost since the reference;
  // - a particle faster than c_s + 2 v_max (c_s the soil's sound speed; v_max the speed the CFL step
  //   covers: the bodies' largest, or a free fall over the wall height): the soil is driven far slower
  //   than sound, so such speed comes from no source;
  // - the soil's kinetic plus potential energy above its reference plus the work the bodies did on
  //   it (plus a margin for the elastic energy the soil can give back).
  std::optional<CrmFailure> check(const CrmSolver& solver) const;

 private:
  long lost0_ = 0;
  double energy0_ = 0, work0_ = 0, slack_ = 0, speed_limit_ = 0;
};

// "N of M active particles (x %) held at the density cap", or empty when none is (particles: the
// soil's count, frozen and lost ones included).
std::string density_cap_note(const SoilStats& stats, std::size_t particles);

// The soil's kinetic plus potential energy [J] (potential from gravity, -g . sum m x).
double soil_mechanical_energy(const SoilStats& stats, const Vec3<double>& gravity);

}  // namespace terracal
