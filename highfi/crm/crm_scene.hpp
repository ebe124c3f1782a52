#pragma once
// A CRM scene, validated once into immutable structs (docs/crm_scene.md): soil, bin, bodies,
// fidelity knobs and the explicit list of effects. Every bad value is an InputError naming key,
// value and range.
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/effect_settings.hpp"
#include "core/range.hpp"
#include "core/rigid_body.hpp"
#include "core/vec.hpp"
#include "highfi/crm/crm_soil.hpp"
#include "highfi/crm/effects/crm_effects.hpp"
#include "highfi/crm/sph_engine.hpp"

namespace terracal {

// The effects a scene names and their settings (highfi/crm/effects/); anything not named costs nothing.
using CrmEffectChoice = EffectChoice<CrmEffects>;

// A scene body is a rigid body of core/rigid_body.hpp (shape, motion program, mass properties).
using CrmBody = RigidBody;

struct CrmBin {
  Vec3<double> size{1, 1, 0.5};  // inner length x, width y, wall height z
  double fill_height = 0.2;
  double fill_length = 0;  // soil occupies x in [0, fill_length]; default the whole bin
  int boundary_layers = 3;
};

struct CrmNumerics {
  double spacing = 0.01;  // d0
  // Why 1.4: docs/decisions.md (the particle lattice is stable under compression from 1.4 on).
  double h_over_d0 = 1.4;
  KernelType kernel = KernelType::kWendlandC2;
  double cfl = 0.3;
  double time_step = 0;       // resolved: given, or cfl h / (c_s + v_expected)
  double expected_speed = 0;  // the v_max used in the CFL limit
  double free_surface_support = 0.8;
  // The velocity boundary markers carry into the soil's velocity gradient and viscosity (scene key
  // resolution.marker_velocity, rigs' --marker-velocity), see MarkerVelocity.
  MarkerVelocity marker_velocity = MarkerVelocity::kMirror;
  // The walls' contact pressure, in units of the soil's own pressure (scene key
  // resolution.wall_contact; 0: off): highfi/crm/wall_contact.hpp, docs/decisions.md.
  double wall_contact = 0;
  int grid_reach = 2;  // neighbour cells of size 2h / reach (1: the plain 2h grid)
  // Cells wider by this fraction, so that the soil and the markers are sorted by cell only once one
  // has moved 2 h sort_skin out of its cell (0: at every step). Why 0.05: docs/decisions.md.
  double sort_skin = 0.05;
  CrmPrecision cpu_precision = CrmPrecision::kDouble;
  double smoothing_length() const { return h_over_d0 * spacing; }
  double cfl_limit(const CrmSoil& soil, double speed) const {
    return 0.3 * smoothing_length() / (soil.sound_speed() + speed);
  }
};

// The ranges of the scene's settings that the rigs' command line takes too (apps/terrain_options.cpp
// checks its options against these same ranges).
struct CrmRanges {
  static constexpr Range kSpacing{0, 1, true, false, "m"};
  static constexpr Range kHOverD0{1.0, 1.6};
  static constexpr Range kTimeStep{0, 1, true, false, "s"};
  static constexpr Range kSettleTime{0, 1e4, false, false, "s"};
  static constexpr Range kSettleJitter{0, 0.3};     // a fraction of the spacing
  static constexpr long kMaxSettleSeed = 1L << 62;  // seeds are whole numbers in [0, 2^62]
};

struct CrmOutputSettings {
  long vtu_every = 0;           // steps between ParaView snapshots; 0 = none
  double vtu_from = 0;          // simulated time from which snapshots are written, s
  long checkpoint_every = 0;    // steps between checkpoints; 0 = only at the end
  double progress_seconds = 5;  // wall seconds between progress lines
};

// What a run tolerates before it stops as failed (crm_run_check.hpp).
struct CrmRunLimits {
  double max_lost_fraction = 1e-3;  // particles that may leave the soil's room, as a fraction of all
};

// The seed of the settling jitter when a scene names none.
constexpr long kDefaultSettleSeed = 20221;

struct CrmScene {
  CrmSoil soil;
  CrmBin bin;
  std::vector<CrmBody> bodies;
  CrmNumerics numerics;
  CrmEffectChoice effects;
  CrmOutputSettings output;
  CrmRunLimits checks;
  double duration = 0;       // simulated seconds after settling
  double settle_time = 0;    // simulated seconds of settling (cached per soil, bin and spacing)
  double settle_jitter = 0;  // settling starts up to this fraction of the spacing off the lattice (seeded)
  // The jitter's seed: another seed is another realisation of the same bed (the pipeline's bin
  // checks average several).
  long settle_seed = kDefaultSettleSeed;
  std::string source;  // where the scene came from, for messages
};

// Validates a scene JSON (see docs/crm_scene.md); `where` names the file in messages.
CrmScene parse_crm_scene(const nlohmann::json& j, const std::string& where);
CrmScene load_crm_scene(const std::filesystem::path& file);
CrmSoil parse_crm_soil(const nlohmann::json& j, const std::string& where);
// Re-checks the invariants of a scene built in code (tests, rigs); throws InputError like the parser.
void validate_crm_scene(CrmScene& scene);
// The names of MarkerVelocity in scenes and on the command line.
inline constexpr const char* kMarkerVelocityNames[] = {"mirror", "mirror_image", "mirror_contact", "wall"};
MarkerVelocity marker_velocity_from_name(const std::string& name);  // throws InputError on others
const char* marker_velocity_name(MarkerVelocity v);

}  // namespace terracal
