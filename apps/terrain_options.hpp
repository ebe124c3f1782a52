#pragma once
// The terrain options shared by `bevameter`, `wheel` and `pipeline`: which solver, which soil, its
// fidelity knobs, and the site (CRM bin sized for the rig, or an SCM patch) built from them.
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "core/terrain.hpp"
#include "highfi/crm_scene.hpp"
#include "lowfi/scm_soil.hpp"
#include "lowfi/scm_terrain.hpp"

namespace terracal::app {

struct TerrainOptions {
  std::string soil_json, scm_json;       // CRM material (DESIGN.md "Soil") or Chrono SCM parameter file
  double spacing = 0.02;                 // CRM particle spacing [m]
  std::string device = "auto";           // cpu | cuda | auto (cuda when a device is present)
  std::string cache = "results/runs/bed_cache";
  double settle_time = 0.3;              // CRM settling [s]
  double settle_jitter = 0;              // CRM settling starts up to this fraction of the spacing off the lattice
  long settle_seed = kDefaultSettleSeed;  // ... drawn with this seed
  // CRM effect hourglass_damping with this alpha (0 = off). On for the rigs: without it the
  // lattice's checkerboard mode softens the bed, more at finer spacing and in deeper bins, and the
  // plate curves neither converge with spacing nor settle with the bin (results/plate_bin_check).
  double hourglass_damping = 0.4;
  // CRM effect hourglass_stiffness with this beta (0 = off). On for the rigs: the damping alone only
  // slows the checkerboard mode, and under a plate the soil keeps escaping through it, so that a
  // held plate loses its force and a slower plate reads less (results/plate_bin_check, tenth study).
  double hourglass_stiffness = 0.03;
  // CRM smoothing length h/d0: 1.4 keeps the particle lattice stable under the bed's own weight
  // (Wendland C2; at 1.2 a column mode grows from round-off and softens the bed: results/crm_settling).
  double h_over_d0 = CrmNumerics{}.h_over_d0;
  // CRM boundary markers' velocity: "mirror" (Adami, DESIGN.md §4), "mirror_image" or "wall" (MarkerVelocity).
  std::string marker_velocity = "mirror";
  double grid = 0.01;                    // SCM grid [m]
  double step = 0;                       // time step [s]; 0 = CRM's CFL step, SCM 1e-3
  std::vector<std::string> scm_effects = {"damping"};
  std::vector<double> gravity;           // SCM: override Earth gravity
  double bin_scale = 1;                  // CRM bins (and their depth) scaled by this: the bin-size check
  double bin_depth_scale = 0;            // the bed's depth scaled by this instead (0 = bin_scale): which dimension matters
  double depth_scale() const { return bin_depth_scale > 0 ? bin_depth_scale : bin_scale; }
};
void add_terrain_options(CLI::App* sub, TerrainOptions& o, bool crm, bool scm);
// --settle-time, --settle-jitter, --hourglass-damping, --hourglass-stiffness, --h-over-d0 and --marker-velocity alone (part of the CRM options above), for
// commands that name the rest of their terrain options themselves (`pipeline`).
void add_crm_settling_options(CLI::App* sub, TerrainOptions& o);

CrmSoil load_crm_soil(const std::string& path);
lowfi::ScmSoil load_scm_soil(const std::string& path);
CrmDevice resolve_device(const std::string& device);

// A CRM site whose bin gives room for a body reaching `reach_x` x `reach_y` from the centre (plus
// `travel` in x), with soil `depth` deep.
std::unique_ptr<TerrainSite> crm_site(const CrmSoil& soil, const TerrainOptions& o, double half_length, double half_width, double depth);
std::unique_ptr<TerrainSite> scm_site(const lowfi::ScmSoil& soil, const TerrainOptions& o, const Vec3<double>& gravity);

// Parses "0,0.2,0.4" into numbers; InputError naming the option.
std::vector<double> parse_list(const std::string& text, const std::string& option);

}  // namespace terracal::app
