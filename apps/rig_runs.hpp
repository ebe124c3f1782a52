#pragma once
// The rigs as the commands run them: sites sized for each rig (a CRM bin per rig, or an SCM patch),
// progress lines on long runs, and the curves with their wall times. Shared by `bevameter`, `wheel`
// and `pipeline`.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "apps/terrain_options.hpp"
#include "lowfi/wong_reece.hpp"
#include "virtual_bevameter/plate_rig.hpp"
#include "virtual_bevameter/shear_rig.hpp"
#include "virtual_bevameter/wheel_rig.hpp"

namespace terracal::app {

// The soil models a rig runs on: CRM (SPH continuum), SCM (Bekker-Wong-Janosi grid), and the
// analytic Wong-Reece wheel model of an SCM set (wheel only).
enum class SoilModel { kCrm, kScm, kWongReece };
// "crm", "scm", "wong-reece": the names the options take and the outputs print.
const std::map<std::string, SoilModel>& soil_model_names();
std::string soil_model_name(SoilModel model);

// One soil seen by either solver: a CRM material or an SCM parameter set.
struct SoilChoice {
  SoilModel solver = SoilModel::kCrm;
  std::optional<CrmSoil> crm;
  std::optional<lowfi::ScmSoil> scm;
  Vec3<double> gravity{0, 0, -9.81};
};

// The allowed values of the bevameter rigs' options: checked on the command line
// (apps/bevameter_options.cpp) and, for plans built in code, by check_bevameter.
struct BevameterRanges {
  static constexpr Range kPlateRadius{0.01, 2, false, false, "m"};
  static constexpr Range kMaxSinkage{1e-3, 2, false, false, "m"};  // and at most 5 plate radii
  static constexpr Range kPlateSpeed{1e-4, 10, false, false, "m/s"};
  static constexpr Range kPlateWallRadii{1.5, 50};
  static constexpr Range kPlateDepthScale{0.5, 10};
  static constexpr Range kAnnulusRadius{0, 10, false, false, "m"};  // inner below outer
  static constexpr Range kShearLoad{1e-3, 1e7, false, false, "N"};
  static constexpr Range kShearAngle{1e-3, 100, false, false, "rad"};
  static constexpr Range kShearRate{1e-3, 100, false, false, "rad/s"};
  static constexpr Range kShearSettle{0, 100, false, false, "s"};
  static constexpr Range kShearLoadRamp{0, 1};  // a fraction of the settling
  static constexpr Range kBinScale{0.5, 10};    // BevameterPlan::bin_scale (the demo's 0.7)
};

struct BevameterPlan {
  std::vector<double> plates{0.2, 0.3};
  double max_sinkage = 0.2, plate_speed = 0.1;
  double plate_unload_speed = 0;  // [m/s] the unload-reload cycle's (0: plate_speed)
  double inner_radius = 0.15, outer_radius = 0.20;
  std::vector<double> shear_loads;  // [N]
  double shear_rate = 1.0, shear_angle = 1.0, shear_settle = 1.0;
  // The annulus's load grows from zero over this fraction of shear_settle, then holds; 0: dropped at
  // once. A dropped ring is still moving when it starts to turn, and how it moves depends on the bin:
  // the start of its torque curve moved 7 % with a 1.5x bin (results/plate_bin_check, twelfth study).
  double shear_load_ramp = 0.5;
  double shear_step = 0;  // CRM time step of the annulus runs; 0 = the terrain's (--step)
  // CRM particle spacing of the plate runs; 0 = the terrain's (--spacing). The plate's checked bin is
  // 3.4x the particles of the annulus's and wheel's per spacing: a coarser plate spacing keeps a
  // pipeline with large plates within one GPU run (with hourglass_damping the plate curve moves
  // 4.7 % from 0.03 to 0.02 m; results/plate_bin_check).
  double plate_spacing = 0;
  // The plate and annulus bins (walls and depth) scaled by this on top of --bin-scale. Below 1 only
  // for the coarse demo, whose bins are smaller than the sizes the bin-size check asks for.
  double bin_scale = 1;
  // The plate's bin (results/plate_bin_check): walls this many plate radii from the centre over
  // plate_depth_scale x (max sinkage + 2.5 radii) of soil. With hourglass_damping on, a bin 1.5x
  // larger than this one changes the loading leg by under 5 % (fifth and sixth studies); the earlier
  // bins (9 radii, 2x; 3 radii, 1x) read 4-8 % and 20-40 % high.
  double plate_wall_radii = 13.5, plate_depth_scale = 3;
};

struct BevameterCurves {
  std::vector<rigs::PlateRow> plate;
  std::vector<rigs::ShearRow> shear;
  // Seconds in the plate runs and in the annulus runs (each with its settling), and from the first
  // run's start to the last one's end: less than their sum when runs go at once.
  double plate_wall = 0, shear_wall = 0, wall = 0;
  std::string site;  // description of the terrain(s)
};

// The slips of a wheel sweep when the user names none (`wheel`, `pipeline`).
inline constexpr const char* kDefaultSlips = "0,0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8";

// Whether CRM runs go at once here (TerrainOptions::concurrent_runs not 1, and CRM on a GPU).
bool crm_runs_go_at_once(const TerrainOptions& o);

// Logs "what: t / t_end s simulated, x real time" every few wall seconds.
rigs::RigProgress progress_logger();

// Every value of a bevameter run, and whether each of its sites fits in memory, checked before any
// site is made: InputError naming the option otherwise. run_bevameter checks the values again.
void check_bevameter(const SoilChoice& soil, const TerrainOptions& o, const BevameterPlan& plan, bool plate,
                     bool shear);
BevameterCurves run_bevameter(const SoilChoice& soil, const TerrainOptions& o, const BevameterPlan& plan, bool plate,
                              bool shear);

// The same for a slip sweep on `solver` (soil.scm and soil.crm may be missing: only the solver, the
// gravity and the resolution matter here).
void check_wheel_sweep(SoilModel solver, const SoilChoice& soil, const TerrainOptions& o, const rigs::WheelSpec& wheel,
                       const std::vector<double>& slips, const rigs::WheelRun& run);
// Warns (once per command) about a sweep that is legitimate but most likely not meant: a wheel that
// does not turn (angular_velocity 0) swept over several slips, which all run the same standstill test.
void warn_about_sweep(const rigs::WheelSpec& wheel, const std::vector<double>& slips);
// A slip sweep on CRM or SCM, or the analytic Wong-Reece model (which needs soil.scm).
std::vector<rigs::WheelResult> run_wheel_sweep(SoilModel solver, const SoilChoice& soil, const TerrainOptions& o,
                                               const rigs::WheelSpec& wheel, const std::vector<double>& slips,
                                               const rigs::WheelRun& run, std::string* site_description = nullptr);

// The site a slip sweep on soil.solver (crm or scm) runs on: room for every slip of `slips` (and
// run.slip_angle's travel across). For runs that share one site (wheel-table).
std::unique_ptr<TerrainSite> wheel_site(const SoilChoice& soil, const TerrainOptions& o, const rigs::WheelSpec& wheel,
                                        const std::vector<double>& slips, const rigs::WheelRun& run);

}  // namespace terracal::app
