#pragma once
// The terrain options shared by `bevameter`, `wheel`, `pipeline` and `demo`: which soil, the solvers'
// fidelity knobs, and the site (a CRM bin sized for the rig, or an SCM patch) built from them. Each
// option is checked on the command line against the range its scene or settings key has.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "apps/cli_fwd.hpp"

#include "core/terrain.hpp"
#include "highfi/crm/crm_scene.hpp"
#include "lowfi/scm_soil.hpp"
#include "lowfi/scm_terrain.hpp"
#include "lowfi/wong_reece.hpp"

namespace terracal::app {

// Where the CRM runs: the CPU, the GPU, or the GPU when one is present.
enum class DeviceChoice { kCpu, kCuda, kAuto };

struct TerrainOptions {
  std::string soil_json, scm_json;  // CRM material (docs/formats.md, "CRM soil") or Chrono SCM set
  double spacing = 0.02;            // CRM particle spacing [m]
  DeviceChoice device = DeviceChoice::kAuto;
  std::string cache = "results/runs/bed_cache";
  double settle_time = 0.3;               // CRM settling [s] (docs/decisions.md)
  double settle_jitter = 0;               // CRM settling starts up to this fraction of the spacing off the lattice
  long settle_seed = kDefaultSettleSeed;  // ... drawn with this seed
  // The CRM effects the rigs name, with these settings (0: off); why: docs/decisions.md.
  double hourglass_damping = HourglassDamping::Settings{}.alpha;
  double hourglass_stiffness = HourglassStiffness::Settings{}.beta;
  double h_over_d0 = CrmNumerics{}.h_over_d0;
  MarkerVelocity marker_velocity = CrmNumerics{}.marker_velocity;
  double grid = 0.01;  // SCM grid [m]
  double step = 0;     // time step [s]; 0 = CRM's CFL step, SCM 1e-3
  std::vector<std::string> scm_effects = {lowfi::ScmDamping::kName};
  std::vector<double> gravity;  // SCM: override Earth gravity
  double wong_reece_tolerance = lowfi::WongReeceOptions{}.rel_tol;  // the entry-angle root and quadratures
  // Wong-Reece with slip sinkage (--wong-reece-slip-sinkage; with --with-wong-reece it follows the SCM
  // effect slip_sinkage).
  bool wong_reece_slip_sinkage = false;
  // CRM runs of one sweep (slips, plates, annulus loads) at once, each on its own host thread and
  // stream; 0: as many as fit, up to kAutoRunsAtOnce, on a GPU, and one on the CPU (whose engine
  // already uses every core). Results do not depend on it; only wall times do.
  int concurrent_runs = 0;
  double bin_scale = 1;         // CRM bins (and their depth) scaled by this: the bin-size check
  double bin_depth_scale = 0;   // the bed's depth scaled by this instead (0 = bin_scale): which dimension matters
  // The options of one solver given on the command line, so that a run on the other solver refuses
  // them instead of ignoring them (choose_soil).
  std::vector<std::string> crm_given, scm_given;
  double depth_scale() const { return bin_depth_scale > 0 ? bin_depth_scale : bin_scale; }
};

// The most CRM runs --concurrent-runs 0 puts on one GPU at once per sweep: the pipeline's two CRM
// stages then drive at most 16 host threads, the cores of the GPU machines measured (bench/RESULTS.md,
// "CRM runs at once"); a larger number was not measured.
inline constexpr int kAutoRunsAtOnce = 8;

// The ranges of the rigs' own options.
struct RigRanges {
  static constexpr Range kConcurrentRuns{0, 64};
  static constexpr Range kBinScale{1, 10};
  static constexpr Range kSpacing{0, 1, true, true, "m"};
  static constexpr Range kScmGrid{1e-4, 1, false, false, "m"};
  static constexpr Range kStep{0, 0.1, false, false, "s"};  // 0: from the CFL limit (CRM), 1e-3 s (SCM)
};

// The CRM options (--soil, --spacing, --device, --concurrent-runs, --cache, the settling options,
// --bin-scale, --bin-depth-scale) and/or the SCM options (--scm, --grid, --scm-effects, --gravity), and --step.
void add_terrain_options(CLI::App* sub, TerrainOptions& o, bool crm, bool scm);
// The CRM options alone; returns --soil.
CLI::Option* add_crm_terrain_options(CLI::App* sub, TerrainOptions& o);
// --grid, the SCM grid spacing.
void add_scm_grid_option(CLI::App* sub, TerrainOptions& o);
// --step, the time step of CRM and SCM.
void add_step_option(CLI::App* sub, TerrainOptions& o);
// The CRM options of the rigs that `pipeline` takes besides its own: --settle-time, --settle-jitter,
// --settle-seed, --hourglass-damping, --hourglass-stiffness, --h-over-d0 and --marker-velocity.
void add_crm_settling_options(CLI::App* sub, TerrainOptions& o);
// --device cpu|cuda|auto.
void add_device_option(CLI::App* sub, DeviceChoice& device);

CrmSoil load_crm_soil(const std::string& path);
lowfi::ScmSoil load_scm_soil(const std::string& path);
// The device a choice means here; InputError for cuda where there is none. resolve_device also
// says on the log where an `auto` CRM runs.
CrmDevice crm_device(DeviceChoice device);
CrmDevice resolve_device(DeviceChoice device);

// The CRM scene of a site whose bin gives room for a body reaching half_length x half_width from the
// centre, with soil `depth` deep (what crm_site settles).
CrmScene crm_site_scene(const CrmSoil& soil, const TerrainOptions& o, double half_length, double half_width,
                        double depth);
// A CRM site whose bin gives room for a body reaching half_length x half_width from the centre, with
// soil `depth` deep.
std::unique_ptr<TerrainSite> crm_site(const CrmSoil& soil, const TerrainOptions& o, double half_length,
                                      double half_width, double depth);
// The SCM effects a --scm-effects list names ("none" and empty entries name none), parsed; throws
// InputError naming --scm-effects and an unknown name.
lowfi::ScmEffectChoice parse_scm_effects_option(const std::vector<std::string>& list);
// Checks one --scm-effects word on the command line (a known effect or none), so a spec that names
// a wrong one is refused before any job runs.
CLI::Validator scm_effect_name();
std::unique_ptr<TerrainSite> scm_site(const lowfi::ScmSoil& soil, const TerrainOptions& o, const Vec3<double>& gravity);

// Parses "0,0.2,0.4" into numbers; InputError naming the option.
std::vector<double> parse_list(const std::string& text, const std::string& option);

}  // namespace terracal::app
