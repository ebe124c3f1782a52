#pragma once
// The SCM soil: Bekker-Wong pressure-sinkage, Mohr-Coulomb strength and Janosi shear, plus the
// elastic stiffness and damping of Chrono's SCM, in Chrono's units (the "Soil parameters" block;
// docs/formats.md, "SCM parameter sets and scm_params.json"): Kc [Pa/m^(n-1)], Kphi [Pa/m^n], n [-],
// cohesion [Pa], friction [deg], Janosi k [m], elastic stiffness [Pa/m], damping [Pa s/m].
#include <array>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "core/range.hpp"
#include "lowfi/slip_sinkage.hpp"

namespace terracal::lowfi {

struct ScmSoil {
  double Kc = 0, Kphi = 2e6, n = 1.1;
  double cohesion = 0, friction_deg = 30, janosi_k = 0.01;
  double elastic_stiffness = 4e7, damping = 3e4;
  // The block "Slip sinkage" beside "Soil parameters" (Lyasko's S): read by the SCM effect
  // slip_sinkage and by Wong-Reece's slip sinkage when they are on; Lyasko's relation if absent.
  SlipSinkage slip_sinkage;

  // Bekker-Wong pressure at sinkage z for a contact of width b: (Kc/b + Kphi) z^n.
  double bekker_pressure(double z, double b) const { return z > 0 ? (Kc / b + Kphi) * std::pow(z, n) : 0.0; }
  // Mohr-Coulomb strength under normal pressure p.
  double shear_strength(double p) const { return cohesion + p * std::tan(friction_deg * M_PI / 180.0); }
  // Janosi-Hanamoto shear stress after shear displacement j under pressure p.
  double janosi_shear(double p, double j) const {
    return shear_strength(p) * (1.0 - std::exp(-std::abs(j) / janosi_k));
  }
};

// One key of the "Soil parameters" block: Chrono's name, the field it sets and its allowed values,
// for the reader and for validate() alike. `required`: Elastic stiffness and Damping default to Chrono's.
struct ScmSoilKey {
  const char* name;
  double ScmSoil::*field;
  Range range;
  bool required;
};
const std::array<ScmSoilKey, 8>& scm_soil_keys();

// Throws InputError "SOURCE: key 'Soil parameters.KEY' = V: expected in RANGE" for the first
// parameter outside its range: for sets built in code (a calibration's result) as the reader checks files.
void validate(const ScmSoil& soil, const std::string& source);

// Reads the "Soil parameters" block of a Chrono SCM JSON file (or of terracal's scm_params.json),
// and the optional block "Slip sinkage" beside it (lowfi/slip_sinkage.hpp).
// Bekker Kphi, Kc, n, the Mohr limits and the Janosi coefficient are required; Elastic stiffness and
// Damping default to Chrono's (4e7, 3e4). Throws InputError naming the file, the key, the value and
// the allowed range.
ScmSoil read_scm_json(const std::string& path);
ScmSoil parse_scm_soil(const nlohmann::json& soil_parameters_block, const std::string& where);
// The "Soil parameters" block, exactly Chrono's names and units.
nlohmann::json scm_soil_json(const ScmSoil& soil);

// The memory an SCM run holds [bytes], estimated before it starts from its grid [m]: a stored node
// for every grid node a body touches over the run (`swept_area` [m^2]; a ScmNode in a hash map), and
// per step the scratch of one ray per node under a body's bounding box (`footprint_area` [m^2]).
double scm_memory_bytes(double grid, double footprint_area, double swept_area);

// Dry sand (Land Locomotion Lab), Wong's Table 2.3 (shared/reference/bekker_wong_soils.csv). Wong
// gives no Janosi k for it; k = 0.025 m is a typical value for loose sand. The soil of the SCM
// tests, the SCM wheel bench and the SCM against Wong-Reece study.
inline ScmSoil reference_dry_sand() {
  ScmSoil s;
  s.n = 1.1;
  s.Kc = 990;
  s.Kphi = 1528430;
  s.cohesion = 1040;
  s.friction_deg = 28;
  s.janosi_k = 0.025;
  return s;
}

}  // namespace terracal::lowfi
