#pragma once
// Single-wheel rig: a rigid wheel under a dead load (its mass; free to sink)
// turning at omega while its carriage moves at v = omega r (1 - s) along the wheel's heading and,
// at a slip angle alpha, v tan(alpha) across it. Drawbar pull, driving torque, lateral force and
// sinkage against time, their steady means over the last part of the run, and slip sweeps (the rows
// of wheel.csv, docs/formats.md).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/range.hpp"
#include "core/terrain.hpp"
#include "virtual_bevameter/rig_progress.hpp"

namespace terracal::rigs {

// The wheel JSON (docs/formats.md, "Wheel").
struct WheelSpec {
  double radius = 0.47, width = 0.25, mass = 108, angular_velocity = 1.0;
  int grouser_count = 0;
  double grouser_height = 0, grouser_thickness = 0;
};
WheelSpec parse_wheel(const nlohmann::json& j, const std::string& where);
// The wheel as parse_wheel reads it (run.json of `terracal wheel` records the wheel it ran).
nlohmann::json wheel_json(const WheelSpec& w);
WheelSpec read_wheel_json(const std::string& path);
void validate(const WheelSpec& w);

// How far across (y) a wheel disturbs the soil, for sizing bins: its half width plus a quarter width
// of undisturbed soil on each side (a bin three wheel widths wide).
inline double wheel_reach_y(const WheelSpec& w) { return 0.75 * w.width; }

// The allowed slips and run settings, checked on the command line (`wheel`, `pipeline`) and by
// validate(WheelRun) and run_wheel.
struct WheelRanges {
  static constexpr Range kSlip{-1, 1, true, true};  // s < 0 is skid
  static constexpr Range kDuration{1e-3, 1e5, false, false, "s"};
  static constexpr Range kAverageFrom{0, 0.95};  // a fraction of the duration
  // The carriage's velocity across the wheel's heading over that along it is tan(slip angle).
  static constexpr Range kSlipAngle{0, 0.7853981633974483, false, false, "rad"};
  // A drop's height: from resting on the surface to a fall of 2 m (6 m/s at the bottom on Earth).
  static constexpr Range kDropHeight{0, 2, false, false, "m"};
};

struct WheelRun {
  double duration = 4.0;      // [s] simulated per slip
  double average_from = 0.5;  // steady means over t >= average_from * duration
  int samples = 200;          // rows of the time series
  // [s] The load grows linearly from zero over this time, as a vehicle's settling puts it on a wheel;
  // 0: all at once (the wheel overshoots its static sinkage and the soil keeps the deeper rut).
  double load_ramp = 0;
  // [rad] The carriage also moves across the wheel (+y, to its left) at v tan(slip_angle), where v
  // is its speed along the heading: the wheel frame's slips are then s and -(1 - s) tan(slip_angle),
  // as a vehicle's tire sees them (core/vehicle/tmeasy.hpp).
  double slip_angle = 0;
  // [m] The wheel starts this far above the undisturbed surface (its lowest point), with no vertical
  // speed, and falls onto the soil under gravity while it turns and travels: a drop test (stability
  // of the contact under impact). 0: it starts resting on the surface.
  double drop_height = 0;
};
void validate(const WheelRun& r);

struct WheelSample {
  double t = 0, x = 0, dbp = 0, torque = 0, sinkage = 0, vertical = 0;
  double lateral = 0;  // the soil's force across the wheel (+y, its left) [N]
};

struct WheelResult {
  double slip = 0, load = 0, slip_angle = 0;
  double dbp = 0, torque = 0, sinkage = 0, lateral = 0;  // steady means
  double dbp_sd = 0, torque_sd = 0, sinkage_sd = 0, lateral_sd = 0;
  // Over every step of the same window: the scatter of the soil's vertical force, and the fraction
  // of steps in which the soil carries less than 5 % of the load (the wheel is off the ground).
  double vertical_sd = 0, airborne_fraction = 0;
  double wall_seconds = 0;
  std::string numerics_note;  // the terrain's note at the end of the run (Terrain::numerics_note)
  std::vector<WheelSample> series;
};

// One run at slip s (-1 < s < 1; s < 0 is skid; omega = 0 is a wheel at standstill under load).
// DBP is the soil's longitudinal force on the wheel (forward positive), torque what the drive applies,
// sinkage the depth of the wheel's lowest point below the undisturbed surface.
WheelResult run_wheel(const TerrainSite& site, const WheelSpec& wheel, double slip, const WheelRun& run,
                      const RigProgress& progress = {});
std::vector<WheelResult> run_slip_sweep(const TerrainSite& site, const WheelSpec& wheel,
                                        const std::vector<double>& slips, const WheelRun& run,
                                        const RigProgress& progress = {});

// Whether the steady means describe a rolling wheel. A wheel off the ground in more than 1 % of the
// averaging window's steps, or whose vertical force scatters by more than a quarter of the load, has
// means that are no steady values (steady runs: SCM 0.2-3.4 %, CRM 3 % at 0.02 m and 14 % in the
// coarse demo at 0.04 m; a hopping SCM wheel 140-260 %): "" when steady, otherwise what was seen,
// for a warning and the reports.
std::string unsteady_reason(const WheelResult& r);
// One Markdown line on a sweep's steadiness: the unsteady runs, or the largest vertical scatter.
std::string steadiness_summary(const std::string& model, const std::vector<WheelResult>& results);

// wheel.csv (slip,load_N,dbp_N,torque_Nm,sinkage_m,dbp_sd_N,torque_sd_Nm; docs/formats.md), atomically;
// and the time series of every slip in one long table.
void write_wheel_csv(const std::string& path, const std::vector<WheelResult>& results);
void write_wheel_series_csv(const std::string& path, const std::vector<WheelResult>& results);

}  // namespace terracal::rigs
