#pragma once
// SCM effect `slip_sinkage`: a slipping contact digs in. Under a node whose surface slips against the
// soil (slip i = 1 - travel / surface speed, lowfi/slip_sinkage.hpp) the soil yields as if its
// pressure-sinkage law were stretched by f(i), sized so that a driven rigid wheel sinks by Lyasko's
// ratio (1 + S i / (1 - 0.5 i)); S from the set's block "Slip sinkage" (Lyasko's 1.5 if absent).
// A plate pressed without slip, and every run without the effect, sees Bekker's law unchanged.
#include "lowfi/effects/scm_effect.hpp"
#include "lowfi/slip_sinkage.hpp"

namespace terracal::lowfi {

struct ScmSlipSinkage : ScmEffect {
  static constexpr const char* kName = "slip_sinkage";
  struct Settings {};
  static constexpr auto settings() { return no_settings<Settings>(); }

  static void yield(const Settings&, const ScmSoil& soil, const Vec3<double>& v, const Vec3<double>& u,
                    const Vec3<double>& nrm, double z, double b, double& p) {
    const double i = surface_slip(v, u, nrm);
    if (i > 0) p = soil.bekker_pressure(z / pressure_sinkage_stretch(soil.slip_sinkage, i, soil.n), b);
  }
};

}  // namespace terracal::lowfi
