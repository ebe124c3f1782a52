#pragma once
// Slip sinkage: a driven wheel digs itself in. Lyasko's relation (M. Lyasko, "LSA model for sinkage
// predictions", Journal of Terramechanics 47 (2010) 1-19) puts a wheel's sinkage at slip i at
//   z(i) = z0 (1 + i) / (1 - 0.5 i),   z0 its sinkage without slip,
// i.e. 3x at i = 0.8. Written as z / z0 = 1 + S i / (1 - 0.5 i), S = 1.5 is Lyasko's relation and S is
// the one parameter of the block "Slip sinkage" in an SCM set (docs/formats.md), so that a
// calibration can fit it (CRM's wheels sink about five-fold from slip 0 to 0.8: S near 3).
//
// The models reach that sinkage by stretching the soil's pressure-sinkage law under a slipping
// contact: p = k (z / f)^n. A rigid wheel on Bekker's law carries W ~ k b sqrt(2 r) z^((2n+1)/2)
// (Bekker's static wheel), so under the stretched law it sinks f^(2n/(2n+1)) times deeper: the
// stretch that gives Lyasko's ratio F is f = F^((2n+1)/(2n)). One source for SCM (effect
// slip_sinkage, per node, from the node's own slip) and Wong-Reece (from the wheel's slip).
#include <algorithm>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "core/vec.hpp"

namespace terracal::lowfi {

struct SlipSinkage {
  double S = 1.5;  // [-] Lyasko's relation; 0: no slip sinkage
};

// The block "Slip sinkage" of an SCM set: {"Model": "Lyasko", "S": S}. Throws InputError naming
// `where`, the key, the value and the allowed range (S in [0, 20]).
SlipSinkage parse_slip_sinkage(const nlohmann::json& block, const std::string& where);
nlohmann::json slip_sinkage_json(const SlipSinkage& s);

// Lyasko's sinkage ratio z(i) / z0 at driving slip i (clamped to [0, 1]; a skidding wheel, i < 0,
// gets none).
inline double slip_sinkage_ratio(const SlipSinkage& p, double i) {
  i = std::clamp(i, 0.0, 1.0);
  return 1.0 + p.S * i / (1.0 - 0.5 * i);
}

// The stretch f of the pressure-sinkage law p = k (z / f)^n that makes a wheel sink by that ratio.
inline double pressure_sinkage_stretch(const SlipSinkage& p, double i, double n) {
  return std::pow(slip_sinkage_ratio(p, i), (2 * n + 1) / (2 * n));
}

// The slip a point of a body's surface sees: 1 - (the body's travel along the surface) / (the
// surface's own speed about the body's centre there), from the point's velocity v, the body's
// translational velocity u and the outward normal nrm. Under a driven wheel's rim this is the
// wheel's slip 1 - v cos(theta) / (omega r); 0 where the surface does not move about the centre (a
// plate) or where it lags the travel (a skid).
inline double surface_slip(const Vec3<double>& v, const Vec3<double>& u, const Vec3<double>& nrm) {
  const Vec3<double> u_tan = u - dot(u, nrm) * nrm;
  const Vec3<double> w = v - u;
  const Vec3<double> w_tan = w - dot(w, nrm) * nrm;
  const double ws = norm(w_tan);
  if (!(ws > 1e-9)) return 0.0;
  return std::clamp(1.0 - norm(u_tan) / ws, 0.0, 1.0);
}

}  // namespace terracal::lowfi
