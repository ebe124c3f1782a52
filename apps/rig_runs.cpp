#include "apps/rig_runs.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/errors.hpp"
#include "virtual_bevameter/rig_checks.hpp"

namespace terracal::app {

namespace {
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::unique_ptr<TerrainSite> site_for(const SoilChoice& soil, const TerrainOptions& o, double half_length,
                                      double half_width, double depth) {
  if (soil.solver == SoilModel::kCrm) {
    if (!soil.crm) throw InputError("--solver crm needs a CRM soil (--soil SOIL.json)");
    return crm_site(*soil.crm, o, o.bin_scale * half_length, o.bin_scale * half_width, o.depth_scale() * depth);
  }
  if (soil.solver == SoilModel::kScm) {
    if (!soil.scm) throw InputError("--solver scm needs an SCM parameter set (--scm SCM.json)");
    return scm_site(*soil.scm, o, soil.gravity);
  }
  throw InputError(fmt::format("solver '{}': the rigs' sites are crm or scm", soil_model_name(soil.solver)));
}

std::vector<rigs::WheelResult> wong_reece_sweep(const SoilChoice& soil, const rigs::WheelSpec& wheel,
                                                const std::vector<double>& slips) {
  if (!soil.scm) throw InputError("--terrain wong-reece needs an SCM parameter set (--scm SCM.json)");
  std::vector<rigs::WheelResult> out;
  for (double s : slips) {
    const auto t0 = Clock::now();
    const auto wr = lowfi::wong_reece(*soil.scm, {wheel.radius, wheel.width}, wheel.mass * norm(soil.gravity), s);
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

BevameterCurves run_bevameter(const SoilChoice& soil, const TerrainOptions& o, const BevameterPlan& plan, bool plate,
                              bool shear) {
  BevameterCurves c;
  rigs::check_range("bevameter bin scale", plan.bin_scale, 0.5, 10, "");
  // Before any run: a bad value must not wait for the plates to finish.
  rigs::check_range("--shear-load-ramp", plan.shear_load_ramp, 0, 1, "(a fraction of --shear-settle)");
  const double k = plan.bin_scale;
  const auto progress = progress_logger();
  if (plate) {
    if (plan.plates.empty()) throw InputError("--plates: give at least one plate radius");
    for (double r : plan.plates) rigs::check_range("--plates radius", r, 0.01, 2, "m");
    rigs::check_range("--max-sinkage", plan.max_sinkage, 1e-3, 2, "m");
    rigs::check_range("--plate-wall-radii", plan.plate_wall_radii, 1.5, 50, "");
    rigs::check_range("--plate-depth-scale", plan.plate_depth_scale, 0.5, 10, "");
    rigs::check_range("--plate-spacing", plan.plate_spacing, 0, 1, "m");
    TerrainOptions po = o;
    if (plan.plate_spacing > 0) po.spacing = plan.plate_spacing;
    const auto t0 = Clock::now();
    for (double r : plan.plates) {
      // Each plate in a bin sized by its own radius (see BevameterPlan::plate_wall_radii).
      const double half = k * plan.plate_wall_radii * r + po.spacing;
      auto site = site_for(soil, po, half, half, k * plan.plate_depth_scale * (plan.max_sinkage + 2.5 * r));
      if (c.site.find(site->description()) == std::string::npos)
        c.site += (c.site.empty() ? "" : "; ") + site->description();
      rigs::PlateTest t;
      t.radius = r;
      t.max_sinkage = plan.max_sinkage;
      t.speed = plan.plate_speed;
      t.thickness = std::max(0.02, 2 * po.spacing);
      const auto rows = rigs::run_plate(*site, t, progress);
      c.plate.insert(c.plate.end(), rows.begin(), rows.end());
      spdlog::info("plate r = {} m: {} rows, force {:.4g} N at {:.3g} m", r, rows.size(), rows.back().force,
                   rows.back().sinkage);
    }
    c.plate_wall = seconds_since(t0);
  }
  if (shear) {
    if (plan.shear_loads.empty()) throw InputError("--shear-loads: give at least one normal load [N]");
    const auto t0 = Clock::now();
    const double r = plan.outer_radius;
    // A thin ring under a heavy load sinks a long way (in CRM 0.19 m for 200 kg on the 0.15-0.20 m
    // annulus): the bed is at least 0.5 m deep, the walls 3 radii away (2 radii: a 1.5x bin moved the torque by 14 %).
    // A thin ring driven into the soil also needs a smaller CRM step than the CFL limit (it fell through the bed at the
    // CFL step; --shear-step).
    TerrainOptions so = o;
    if (plan.shear_step > 0) so.step = plan.shear_step;
    auto site = site_for(soil, so, k * 3 * r + o.spacing, k * 3 * r + o.spacing, k * std::max(0.5, 2.5 * r));
    if (c.site.empty()) c.site = site->description();
    rigs::ShearTest t;
    t.inner_radius = plan.inner_radius;
    t.outer_radius = plan.outer_radius;
    t.loads = plan.shear_loads;
    t.angular_velocity = plan.shear_rate;
    t.max_angle = plan.shear_angle;
    t.settle_time = plan.shear_settle;
    t.load_ramp = plan.shear_load_ramp * plan.shear_settle;
    t.thickness = std::max(0.02, 2 * o.spacing);
    c.shear = rigs::run_shear(*site, t, progress);
    c.shear_wall = seconds_since(t0);
  }
  return c;
}

std::vector<rigs::WheelResult> run_wheel_sweep(SoilModel solver, const SoilChoice& soil, const TerrainOptions& o,
                                               const rigs::WheelSpec& wheel, const std::vector<double>& slips,
                                               const rigs::WheelRun& run, std::string* site_description) {
  rigs::validate(wheel);
  rigs::validate(run);
  for (double s : slips)
    if (!(s > -1 && s < 1)) throw InputError(fmt::format("--slips: slip {} outside (-1, 1)", s));
  if (solver == SoilModel::kWongReece) {
    if (site_description) *site_description = "Wong-Reece (analytic, GSL quadrature)";
    return wong_reece_sweep(soil, wheel, slips);
  }
  SoilChoice s = soil;
  s.solver = solver;
  // The bin: the run's travel at the lowest slip plus two outer radii of soil before and after.
  double travel = 0;
  for (double slip : slips)
    travel = std::max(travel, wheel.angular_velocity * wheel.radius * (1 - slip) * run.duration);
  const double outer = wheel.radius + wheel.grouser_height;
  auto site = site_for(s, o, 0.5 * travel + 2 * outer + o.spacing, 2 * rigs::wheel_reach_y(wheel) + o.spacing,
                       std::max(0.2, 0.5 * wheel.radius));
  if (site_description) *site_description = site->description();
  std::vector<rigs::WheelResult> out;
  const auto progress = progress_logger();
  for (double slip : slips) {
    out.push_back(rigs::run_wheel(*site, wheel, slip, run, progress));
    const auto& r = out.back();
    spdlog::info("{} wheel at slip {}: DBP {:.4g} N, torque {:.4g} N m, sinkage {:.4g} m ({:.3g} s wall)",
                 soil_model_name(solver), slip, r.dbp, r.torque, r.sinkage, r.wall_seconds);
    if (const std::string why = rigs::unsteady_reason(r); !why.empty())
      spdlog::warn("{} {} (wheel_series.csv has the time series)", soil_model_name(solver), why);
  }
  return out;
}

}  // namespace terracal::app
