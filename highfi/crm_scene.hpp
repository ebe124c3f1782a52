#pragma once
// A CRM scene, validated once into immutable structs (DESIGN.md §2): soil, bin, bodies, fidelity
// knobs and the explicit list of effects. Every bad value is an InputError naming key, value and range.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/rigid_body.hpp"
#include "core/quat.hpp"
#include "core/vec.hpp"
#include "highfi/sph_engine.hpp"

namespace terracal {

// The CRM material (DESIGN.md §3 "Soil").
struct CrmSoil {
  double density = 1700, young_modulus = 1e6, poisson_ratio = 0.3, mu_s = 0.7, mu_2 = 0.7, I0 = 0.03;
  double grain_diameter = 0.005, cohesion = 0;
  Vec3<double> gravity{0, 0, -9.81};
  double shear_modulus() const { return young_modulus / (2 * (1 + poisson_ratio)); }
  double bulk_modulus() const { return young_modulus / (3 * (1 - 2 * poisson_ratio)); }
  double sound_speed() const { return std::sqrt(bulk_modulus() / density); }
};

// Effects a scene may name; anything not named costs nothing.
struct CrmEffects {
  bool cohesion = false, artificial_viscosity = false, shifting = false, active_domain = false, hourglass_damping = false;
  bool hourglass_stiffness = false;
};
inline const std::array<const char*, 6> kCrmEffectNames = {"cohesion", "artificial_viscosity", "shifting", "active_domain",
                                                           "hourglass_damping", "hourglass_stiffness"};

// A scene body is a rigid body of core/rigid_body.hpp (shape, motion program, mass properties).
using CrmBody = RigidBody;

struct CrmBin {
  Vec3<double> size{1, 1, 0.5};  // inner length x, width y, wall height z
  double fill_height = 0.2;
  double fill_length = 0;        // soil occupies x in [0, fill_length]; default the whole bin
  int boundary_layers = 3;
};

struct CrmNumerics {
  double spacing = 0.01;       // d0
  // h/d0 1.4: with the Wendland C2 kernel at 1.2 the particle lattice is unstable under compression
  // (a column mode the velocity gradient does not see; results/crm_settling, "lattice stability"),
  // at 1.4 it is stable for every compressive stress (highfi/lattice_stability.hpp).
  double h_over_d0 = 1.4;
  KernelType kernel = KernelType::kWendlandC2;
  double cfl = 0.3;
  double time_step = 0;        // resolved: given, or cfl h / (c_s + v_expected)
  double expected_speed = 0;   // the v_max used in the CFL limit
  double viscosity_alpha = 0.1;
  double xsph = 0.5;
  double hourglass_alpha = 0.4;   // hourglass damping: nu = alpha h c_s / 10 (Monaghan's alpha on the same scale; 0.4: results/plate_bin_check)
  // hourglass stiffness: a spring k = beta E / (rho0 h^2) on each particle's displacement that its
  // neighbourhood's velocity gradient does not explain (highfi/sph_stage.hpp, HourglassShare;
  // 0.03: results/plate_bin_check, tenth study)
  double hourglass_beta = 0.03;
  double active_margin = 0.1;
  double free_surface_support = 0.8;
  // The velocity boundary markers carry into the soil's velocity gradient and viscosity (scene key
  // resolution.marker_velocity, rigs' --marker-velocity), see MarkerVelocity.
  MarkerVelocity marker_velocity = MarkerVelocity::kMirror;
  int grid_reach = 2;          // neighbour cells of size 2h / reach (1: the 2h grid of DESIGN.md)
  CrmPrecision cpu_precision = CrmPrecision::kDouble;
  double smoothing_length() const { return h_over_d0 * spacing; }
  double cfl_limit(const CrmSoil& soil, double speed) const {
    return 0.3 * smoothing_length() / (soil.sound_speed() + speed);
  }
};

struct CrmOutputSettings {
  long vtu_every = 0;          // steps between ParaView snapshots; 0 = none
  long checkpoint_every = 0;   // steps between checkpoints; 0 = only at the end
  double progress_seconds = 5; // wall seconds between progress lines
};

constexpr long kDefaultSettleSeed = 20221;

struct CrmScene {
  CrmSoil soil;
  CrmBin bin;
  std::vector<CrmBody> bodies;
  CrmNumerics numerics;
  CrmEffects effects;
  CrmOutputSettings output;
  double duration = 0;         // simulated seconds after settling
  double settle_time = 0;      // simulated seconds of settling (cached per soil, bin and spacing)
  double settle_jitter = 0;    // settling starts up to this fraction of the spacing off the lattice (seeded)
  // The jitter's seed: another seed is another realisation of the same bed (the pipeline's bin
  // checks average several). 20221 is the seed every bed used before the key existed.
  long settle_seed = kDefaultSettleSeed;
  std::string source;          // where the scene came from, for messages
};

// Validates a scene JSON (see docs/crm_scene.md); `where` names the file in messages.
CrmScene parse_crm_scene(const nlohmann::json& j, const std::string& where);
CrmScene load_crm_scene(const std::filesystem::path& file);
CrmSoil parse_crm_soil(const nlohmann::json& j, const std::string& where);
// Re-checks the invariants of a scene built in code (tests, rigs); throws InputError like the parser.
void validate_crm_scene(CrmScene& scene);
// The names of MarkerVelocity in scenes and on the command line: mirror, mirror_image, wall.
MarkerVelocity marker_velocity_from_name(const std::string& name);  // throws InputError on others
const char* marker_velocity_name(MarkerVelocity v);

}  // namespace terracal
