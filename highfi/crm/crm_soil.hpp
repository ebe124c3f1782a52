#pragma once
// The CRM material (docs/formats.md, "CRM soil"): the soil a scene, a rig or a pipeline simulates.
#include <cmath>

#include "core/vec.hpp"

namespace terracal {

struct CrmSoil {
  double density = 1700, young_modulus = 1e6, poisson_ratio = 0.3, mu_s = 0.7, mu_2 = 0.7, I0 = 0.03;
  double grain_diameter = 0.005, cohesion = 0;
  Vec3<double> gravity{0, 0, -9.81};
  double shear_modulus() const { return young_modulus / (2 * (1 + poisson_ratio)); }
  double bulk_modulus() const { return young_modulus / (3 * (1 - 2 * poisson_ratio)); }
  double sound_speed() const { return std::sqrt(bulk_modulus() / density); }
};

}  // namespace terracal
