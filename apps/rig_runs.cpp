#include "apps/rig_runs.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <mutex>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "apps/memory_check.hpp"
#include "core/concurrent_jobs.hpp"
#include "core/errors.hpp"

namespace terracal::app {

namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// The soil a rig needs: a CRM bin (half length and half width around the centre and the soil's
// depth, before --bin-scale), and for SCM's memory the areas under its body in one step and over
// the whole run [m^2]. `spacing_option` names the option that sets the CRM spacing of its runs.
struct RigSoil {
  std::string what;
  double half_length = 0, half_width = 0, depth = 0;
  double footprint = 0, swept = 0;
  std::string spacing_option = "--spacing";
};

// Each plate in a bin sized by its own radius (see BevameterPlan::plate_wall_radii).
RigSoil plate_soil(const BevameterPlan& plan, const TerrainOptions& po, double r) {
  const double k = plan.bin_scale, half = k * plan.plate_wall_radii * r + po.spacing;
  const double depth = k * plan.plate_depth_scale * (plan.max_sinkage + 2.5 * r);
  return {fmt::format("the plate r = {} m", r),
          half,
          half,
          depth,
          4 * r * r,
          4 * r * r,
          plan.plate_spacing > 0 ? "--plate-spacing" : "--spacing"};
}

// A thin ring under a heavy load sinks a long way (in CRM 0.19 m for 200 kg on the 0.15-0.20 m
// annulus): the bed is at least 0.5 m deep, the walls 3 radii away (2 radii: a 1.5x bin moved the
// torque by 14 %).
RigSoil shear_soil(const BevameterPlan& plan, const TerrainOptions& o) {
  const double k = plan.bin_scale, r = plan.outer_radius, half = k * 3 * r + o.spacing;
  return {"the annulus", half, half, k * std::max(0.5, 2.5 * r), 4 * r * r, 4 * r * r};
}

// The run's travel at the lowest slip plus two outer radii of soil before and after.
RigSoil wheel_soil(const rigs::WheelSpec& wheel, const std::vector<double>& slips, const rigs::WheelRun& run,
                   const TerrainOptions& o) {
  double travel = 0;
  for (double slip : slips)
    travel = std::max(travel, wheel.angular_velocity * wheel.radius * (1 - slip) * run.duration);
  const double outer = wheel.radius + wheel.grouser_height;
  const double cross = travel * std::tan(run.slip_angle);
  return {"the wheel",
          0.5 * travel + 2 * outer + o.spacing,
          0.5 * cross + 2 * rigs::wheel_reach_y(wheel) + o.spacing,
          std::max(0.2, 0.5 * wheel.radius),
          2 * outer * wheel.width,
          (2 * outer + travel) * (wheel.width + cross)};
}

// The CRM scene of `rig`'s site (its bin scaled by --bin-scale and --bin-depth-scale).
CrmScene rig_scene(const CrmSoil& soil, const TerrainOptions& o, const RigSoil& rig) {
  return crm_site_scene(soil, o, o.bin_scale * rig.half_length, o.bin_scale * rig.half_width,
                        o.depth_scale() * rig.depth);
}

// One CRM run of a command: its site, and the options the site is built with (the plates' spacing
// may differ from the others').
struct CrmJob {
  TerrainOptions o;
  RigSoil rig;
};

// How many of the CRM runs `jobs` go at once (TerrainOptions::concurrent_runs): the option's value,
// or with 0 on a GPU up to kAutoRunsAtOnce, as many as fit with the largest runs together. An explicit
// value that does not fit is refused (InputError naming --concurrent-runs); auto takes fewer.
int runs_at_once(const SoilChoice& soil, const TerrainOptions& o, const std::vector<CrmJob>& jobs) {
  if (soil.solver != SoilModel::kCrm || !soil.crm || jobs.size() <= 1 || o.concurrent_runs == 1) return 1;
  const bool gpu = crm_device(o.device) == CrmDevice::kCuda;
  int width = int(std::min<std::size_t>(jobs.size(), std::size_t(o.concurrent_runs > 0 ? o.concurrent_runs
                                                                  : gpu ? kAutoRunsAtOnce
                                                                        : 1)));
  if (width <= 1) return 1;
  std::vector<std::pair<double, double>> bytes;
  for (const CrmJob& job : jobs) {
    const CrmMemoryNeed n = crm_memory_need(rig_scene(*soil.crm, job.o, job.rig), crm_device(job.o.device));
    bytes.push_back({n.host_bytes, n.gpu_bytes});
  }
  std::sort(bytes.begin(), bytes.end(), [](const auto& a, const auto& b) { return a.second + a.first > b.second + b.first; });
  const double host = available_host_bytes(), device = gpu ? available_gpu_bytes() : -1;
  for (; width > 1; --width) {
    double h = 0, d = 0;
    for (int k = 0; k < width; ++k) h += bytes[std::size_t(k)].first, d += bytes[std::size_t(k)].second;
    if ((host < 0 || h <= host) && (device < 0 || d <= device)) return width;
    if (o.concurrent_runs > 0)
      throw InputError(fmt::format(
          "--concurrent-runs {}: {} CRM runs at once need about {:.3g} GiB of memory and {:.3g} GiB on the GPU, where "
          "{:.3g} GiB and {:.3g} GiB are free; expected fewer runs at once (0: as many as fit)",
          o.concurrent_runs, width, h / 1073741824.0, d / 1073741824.0, host / 1073741824.0,
          std::max(device, 0.0) / 1073741824.0));
  }
  return 1;
}

// Refuses a site that cannot fit in memory, naming the options that size it; `say`: log the estimate.
void check_site_memory(const SoilChoice& soil, const TerrainOptions& o, const RigSoil& rig, bool say = false) {
  if (soil.solver == SoilModel::kCrm && soil.crm) {
    const CrmScene sc = rig_scene(*soil.crm, o, rig);
    check_crm_memory(sc, crm_device(o.device), fmt::format("{} {} m", rig.spacing_option, o.spacing),
                     fmt::format("a coarser {} (or a smaller --bin-scale) for {}", rig.spacing_option, rig.what), say);
  } else if (soil.solver == SoilModel::kScm) {
    check_memory(fmt::format("--grid {} m", o.grid),
                 fmt::format("SCM under {} ({:.3g} m^2 of soil touched)", rig.what, rig.swept),
                 lowfi::scm_memory_bytes(o.grid, rig.footprint, rig.swept), 0, "a coarser --grid", say);
  }
}

std::unique_ptr<TerrainSite> site_for(const SoilChoice& soil, const TerrainOptions& o, const RigSoil& rig) {
  check_site_memory(soil, o, rig, true);  // again: memory may have gone since the plan was checked
  if (soil.solver == SoilModel::kCrm) {
    if (!soil.crm) throw InputError("--solver crm needs a CRM soil (--soil SOIL.json)");
    return crm_site(*soil.crm, o, o.bin_scale * rig.half_length, o.bin_scale * rig.half_width,
                    o.depth_scale() * rig.depth);
  }
  if (soil.solver == SoilModel::kScm) {
    if (!soil.scm) throw InputError("--solver scm needs an SCM parameter set (--scm SCM.json)");
    return scm_site(*soil.scm, o, soil.gravity);
  }
  throw InputError(fmt::format("solver '{}': the rigs' sites are crm or scm", soil_model_name(soil.solver)));
}

std::vector<rigs::WheelResult> wong_reece_sweep(const SoilChoice& soil, const rigs::WheelSpec& wheel,
                                                const std::vector<double>& slips, const TerrainOptions& o) {
  lowfi::WongReeceOptions options;
  options.rel_tol = o.wong_reece_tolerance;
  options.slip_sinkage =
      o.wong_reece_slip_sinkage ||
      std::count(o.scm_effects.begin(), o.scm_effects.end(), std::string(lowfi::ScmSlipSinkage::kName)) > 0;
  if (!soil.scm) throw InputError("--terrain wong-reece needs an SCM parameter set (--scm SCM.json)");
  std::vector<rigs::WheelResult> out;
  for (double s : slips) {
    const auto t0 = Clock::now();
    const auto wr = lowfi::wong_reece(*soil.scm, {wheel.radius, wheel.width}, wheel.mass * norm(soil.gravity), s, options);
    rigs::WheelResult r;
    r.slip = s;
    r.load = wr.load;
    r.dbp = wr.dbp;
    r.torque = wr.torque;
    r.sinkage = wr.sinkage;
    r.wall_seconds = seconds_since(t0);
    out.push_back(r);
  }
  return out;
}

// The plates' values (before any plate runs: a bad value must not wait for the others to finish).
void check_plate_plan(const BevameterPlan& plan) {
  using R = BevameterRanges;
  if (plan.plates.empty()) throw InputError("--plates: give at least one plate radius");
  for (double r : plan.plates) {
    check_range(R::kPlateRadius, r, "--plates");
    if (plan.max_sinkage > 5 * r)
      throw InputError(
          fmt::format("--max-sinkage {} m: more than 5 radii of the plate r = {} m (--plates); expected "
                      "at most {} m",
                      plan.max_sinkage, r, 5 * r));
  }
  check_distinct(plan.plates, "--plates",
                 "each plate radius is run once (plate.csv keys a plate's curve by its radius)");
  check_range(R::kMaxSinkage, plan.max_sinkage, "--max-sinkage");
  check_range(R::kPlateSpeed, plan.plate_speed, "--plate-speed");
  if (plan.plate_unload_speed != 0) check_range(R::kPlateSpeed, plan.plate_unload_speed, "--plate-unload-speed");
  check_range(R::kPlateWallRadii, plan.plate_wall_radii, "--plate-wall-radii");
  check_range(R::kPlateDepthScale, plan.plate_depth_scale, "--plate-depth-scale");
  if (plan.plate_spacing != 0) check_range(RigRanges::kSpacing, plan.plate_spacing, "--plate-spacing");
}

void check_shear_plan(const BevameterPlan& plan) {
  using R = BevameterRanges;
  if (plan.shear_loads.empty()) throw InputError("--shear-loads: give at least one normal load [N]");
  for (double load : plan.shear_loads) check_range(R::kShearLoad, load, "--shear-loads");
  check_range(R::kAnnulusRadius, plan.inner_radius, "--annulus (inner radius)");
  check_range(R::kAnnulusRadius, plan.outer_radius, "--annulus (outer radius)");
  if (!(plan.outer_radius > plan.inner_radius))
    throw InputError(fmt::format("--annulus {},{}: expected the inner radius below the outer one", plan.inner_radius,
                                 plan.outer_radius));
  check_range(R::kShearAngle, plan.shear_angle, "--shear-angle");
  check_range(R::kShearRate, plan.shear_rate, "--shear-rate");
  check_range(R::kShearSettle, plan.shear_settle, "--shear-settle");
  check_range(R::kShearLoadRamp, plan.shear_load_ramp, "--shear-load-ramp");
  check_range(RigRanges::kStep, plan.shear_step, "--shear-step");
}

void check_bevameter_plan(const BevameterPlan& plan, bool plate, bool shear) {
  check_range(BevameterRanges::kBinScale, plan.bin_scale, "bevameter bin scale");
  if (plate) check_plate_plan(plan);
  if (shear) check_shear_plan(plan);
}

TerrainOptions plate_options(const BevameterPlan& plan, const TerrainOptions& o) {
  TerrainOptions po = o;
  if (plan.plate_spacing > 0) po.spacing = plan.plate_spacing;
  return po;
}

// A thin ring driven into the soil needs a smaller CRM step than the CFL limit (it fell through the
// bed at the CFL step): --shear-step.
TerrainOptions shear_options(const BevameterPlan& plan, const TerrainOptions& o) {
  TerrainOptions so = o;
  if (plan.shear_step > 0) so.step = plan.shear_step;
  return so;
}
}  // namespace

const std::map<std::string, SoilModel>& soil_model_names() {
  static const std::map<std::string, SoilModel> names{
      {"crm", SoilModel::kCrm}, {"scm", SoilModel::kScm}, {"wong-reece", SoilModel::kWongReece}};
  return names;
}

std::string soil_model_name(SoilModel model) {
  for (const auto& [name, m] : soil_model_names())
    if (m == model) return name;
  return "?";
}

bool crm_runs_go_at_once(const TerrainOptions& o) {
  if (o.concurrent_runs == 1) return false;
  return o.concurrent_runs > 1 || crm_device(o.device) == CrmDevice::kCuda;
}

rigs::RigProgress progress_logger() {
  auto start = std::make_shared<Clock::time_point>(Clock::now());
  auto last = std::make_shared<Clock::time_point>(Clock::now());
  auto current = std::make_shared<std::string>();
  return [=](const std::string& what, double t, double t_end) {
    if (what != *current) {
      *current = what;
      *start = Clock::now();
      *last = *start;
      return;
    }
    if (seconds_since(*last) < 5 && t < t_end) return;
    *last = Clock::now();
    const double wall = seconds_since(*start);
    spdlog::info("{}: {:.3g} / {:.3g} s simulated, {:.3g} s wall ({:.3g}x real time)", what, t, t_end, wall,
                 wall > 0 ? t / wall : 0);
  };
}

namespace {
rigs::PlateTest plate_test(const BevameterPlan& plan, const TerrainOptions& po, double r) {
  rigs::PlateTest t;
  t.radius = r;
  t.max_sinkage = plan.max_sinkage;
  t.speed = plan.plate_speed;
  t.unload_speed = plan.plate_unload_speed;
  t.thickness = std::max(0.02, 2 * po.spacing);
  return t;
}

rigs::ShearTest shear_test(const BevameterPlan& plan, const TerrainOptions& o, double load) {
  rigs::ShearTest t;
  t.inner_radius = plan.inner_radius;
  t.outer_radius = plan.outer_radius;
  t.loads = {load};
  t.angular_velocity = plan.shear_rate;
  t.max_angle = plan.shear_angle;
  t.settle_time = plan.shear_settle;
  t.load_ramp = plan.shear_load_ramp * plan.shear_settle;
  t.thickness = std::max(0.02, 2 * o.spacing);
  return t;
}

// The bevameter's runs as a list of jobs: each plate (in a bin of its own), then each annulus load
// (all on one bin, settled by the first load's job).
struct BevameterJobs {
  std::vector<double> plates, loads;
  std::vector<CrmJob> rigs;  // per job, for the memory of runs at once
  std::size_t size() const { return plates.size() + loads.size(); }
};

BevameterJobs bevameter_jobs(const TerrainOptions& o, const BevameterPlan& plan, bool plate, bool shear) {
  BevameterJobs j;
  const TerrainOptions po = plate_options(plan, o);
  if (plate)
    for (double r : plan.plates) j.plates.push_back(r), j.rigs.push_back({po, plate_soil(plan, po, r)});
  const TerrainOptions so = shear_options(plan, o);
  if (shear)
    for (double load : plan.shear_loads) j.loads.push_back(load), j.rigs.push_back({so, shear_soil(plan, o)});
  return j;
}
}  // namespace

BevameterCurves run_bevameter(const SoilChoice& soil, const TerrainOptions& o, const BevameterPlan& plan, bool plate,
                              bool shear) {
  // Before any run: a bad value must not wait for the plates to finish.
  check_bevameter_plan(plan, plate, shear);
  const auto t0 = Clock::now();
  const BevameterJobs jobs = bevameter_jobs(o, plan, plate, shear);
  const int width = runs_at_once(soil, o, jobs.rigs);
  if (width > 1) spdlog::info("bevameter: {} CRM runs, {} at once", jobs.size(), width);
  const TerrainOptions po = plate_options(plan, o), so = shear_options(plan, o);
  std::vector<std::vector<rigs::PlateRow>> plate_rows(jobs.plates.size());
  std::vector<std::vector<rigs::ShearRow>> shear_rows(jobs.loads.size());
  std::vector<std::string> plate_sites(jobs.plates.size());
  std::vector<double> seconds(jobs.size(), 0.0);
  std::unique_ptr<TerrainSite> annulus;
  std::once_flag annulus_settled;
  run_concurrently(jobs.size(), width, [&](std::size_t i) {
    const auto t = Clock::now();
    const auto progress = progress_logger();
    if (i < jobs.plates.size()) {
      const double r = jobs.plates[i];
      auto site = site_for(soil, po, plate_soil(plan, po, r));
      plate_sites[i] = site->description();
      plate_rows[i] = rigs::run_plate(*site, plate_test(plan, po, r), progress);
      const auto& rows = plate_rows[i];
      spdlog::info("plate r = {} m: {} rows, force {:.4g} N at {:.3g} m", r, rows.size(), rows.back().force,
                   rows.back().sinkage);
    } else {
      const std::size_t k = i - jobs.plates.size();
      std::call_once(annulus_settled, [&] { annulus = site_for(soil, so, shear_soil(plan, o)); });
      shear_rows[k] = rigs::run_shear(*annulus, shear_test(plan, o, jobs.loads[k]), progress);
    }
    seconds[i] = seconds_since(t);
  });
  BevameterCurves c;
  for (std::size_t i = 0; i < jobs.plates.size(); ++i) {
    c.plate.insert(c.plate.end(), plate_rows[i].begin(), plate_rows[i].end());
    if (c.site.find(plate_sites[i]) == std::string::npos) c.site += (c.site.empty() ? "" : "; ") + plate_sites[i];
    c.plate_wall += seconds[i];
  }
  for (std::size_t k = 0; k < jobs.loads.size(); ++k) {
    c.shear.insert(c.shear.end(), shear_rows[k].begin(), shear_rows[k].end());
    c.shear_wall += seconds[jobs.plates.size() + k];
  }
  if (annulus && c.site.empty()) c.site = annulus->description();
  c.wall = seconds_since(t0);
  return c;
}

void check_bevameter(const SoilChoice& soil, const TerrainOptions& o, const BevameterPlan& plan, bool plate,
                     bool shear) {
  check_bevameter_plan(plan, plate, shear);
  if (plate) {
    const TerrainOptions po = plate_options(plan, o);
    for (double r : plan.plates) check_site_memory(soil, po, plate_soil(plan, po, r));
  }
  if (shear) check_site_memory(soil, shear_options(plan, o), shear_soil(plan, o));
  runs_at_once(soil, o, bevameter_jobs(o, plan, plate, shear).rigs);
}

void check_wheel_sweep(SoilModel solver, const SoilChoice& soil, const TerrainOptions& o, const rigs::WheelSpec& wheel,
                       const std::vector<double>& slips, const rigs::WheelRun& run) {
  rigs::validate(wheel);
  rigs::validate(run);
  if (slips.empty()) throw InputError("--slips: give at least one slip");
  for (double s : slips) check_range(rigs::WheelRanges::kSlip, s, "--slips");
  if (solver == SoilModel::kWongReece) return;
  SoilChoice s = soil;
  s.solver = solver;
  const RigSoil rig = wheel_soil(wheel, slips, run, o);
  check_site_memory(s, o, rig);
  runs_at_once(s, o, std::vector<CrmJob>(slips.size(), CrmJob{o, rig}));
}

void warn_about_sweep(const rigs::WheelSpec& wheel, const std::vector<double>& slips) {
  if (wheel.angular_velocity == 0 && slips.size() > 1)
    spdlog::warn(
        "the wheel's angular_velocity is 0: it does not turn, and every slip of --slips is the same "
        "standstill run under its load");
}

std::vector<rigs::WheelResult> run_wheel_sweep(SoilModel solver, const SoilChoice& soil, const TerrainOptions& o,
                                               const rigs::WheelSpec& wheel, const std::vector<double>& slips,
                                               const rigs::WheelRun& run, std::string* site_description) {
  rigs::validate(wheel);
  rigs::validate(run);
  for (double s : slips) check_range(rigs::WheelRanges::kSlip, s, "--slips");
  if (solver == SoilModel::kWongReece) {
    if (site_description) *site_description = "Wong-Reece (analytic, GSL quadrature)";
    return wong_reece_sweep(soil, wheel, slips, o);
  }
  SoilChoice s = soil;
  s.solver = solver;
  const RigSoil rig = wheel_soil(wheel, slips, run, o);
  auto site = site_for(s, o, rig);
  if (site_description) *site_description = site->description();
  // Every slip is its own run on the one settled bed: on a GPU they go at once (runs_at_once).
  const int width = runs_at_once(s, o, std::vector<CrmJob>(slips.size(), CrmJob{o, rig}));
  if (width > 1) spdlog::info("wheel: {} CRM runs, {} at once", slips.size(), width);
  std::vector<rigs::WheelResult> out(slips.size());
  run_concurrently(slips.size(), width, [&](std::size_t i) {
    out[i] = rigs::run_wheel(*site, wheel, slips[i], run, progress_logger());
    const auto& r = out[i];
    spdlog::info("{} wheel at slip {}: DBP {:.4g} N, torque {:.4g} N m, sinkage {:.4g} m ({:.3g} s wall){}",
                 soil_model_name(solver), slips[i], r.dbp, r.torque, r.sinkage, r.wall_seconds,
                 r.numerics_note.empty() ? "" : "; at the end " + r.numerics_note);
    if (const std::string why = rigs::unsteady_reason(r); !why.empty())
      spdlog::warn("{} {} (wheel_series.csv has the time series)", soil_model_name(solver), why);
  });
  return out;
}

std::unique_ptr<TerrainSite> wheel_site(const SoilChoice& soil, const TerrainOptions& o, const rigs::WheelSpec& wheel,
                                        const std::vector<double>& slips, const rigs::WheelRun& run) {
  return site_for(soil, o, wheel_soil(wheel, slips, run, o));
}

}  // namespace terracal::app
