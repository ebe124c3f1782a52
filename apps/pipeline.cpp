#include "apps/pipeline.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "apps/calibration_run.hpp"
#include "apps/pipeline_checks.hpp"
#include "apps/pipeline_report.hpp"
#include "apps/report_plots.hpp"
#include "apps/soil_choice.hpp"
#include "apps/wheel_band.hpp"
#include "core/concurrent_jobs.hpp"
#include "core/csv.hpp"
#include "core/errors.hpp"
#include "lowfi/effects/scm_slip_sinkage.hpp"
#include "lowfi/scm_terrain.hpp"

namespace terracal::app {

namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// 1. The CRM bevameter: plates and annulus; the curves go to OUT/bevameter/.
BevameterCurves bevameter_stage(const PipelinePlan& plan, const SoilChoice& crm, StageTimes& wall) {
  const BevameterPlan& b = plan.bevameter;
  spdlog::info("pipeline 1/4: CRM bevameter (plates {} m to {} m, annulus {}-{} m at {} loads)",
               fmt::join(b.plates, ", "), b.max_sinkage, b.inner_radius, b.outer_radius, b.shear_loads.size());
  const auto t = Clock::now();
  BevameterCurves bev = run_bevameter(crm, plan.terrain, b, true, true);
  wall.bevameter = since(t);
  const std::string dir = plan.out + "/bevameter";
  std::filesystem::create_directories(dir);
  rigs::write_plate_csv(dir + "/plate.csv", bev.plate);
  rigs::write_shear_csv(dir + "/shear.csv", bev.shear);
  return bev;
}

CalibrationSettings calibration_settings(const PipelinePlan& plan, const std::string& folder) {
  CalibrationSettings s;
  s.out_dir = plan.out + "/" + folder;
  s.seed = plan.seed;
  s.annulus_law = plan.calibrate_on_wheel ? plan.annulus_law : bayes::AnnulusLaw::kShared;
  s.elastic_stiffness = plan.elastic_stiffness;
  return s;
}

// 2. The calibration, on the curves in memory, into OUT/calibration/.
CalibrationOutcome calibration_stage(const PipelinePlan& plan, const CalibrationData& data, StageTimes& wall) {
  spdlog::info("pipeline 2/4: calibrating SCM on the CRM {}", data.wheel ? "bevameter and wheel curves" : "bevameter curves");
  const auto t = Clock::now();
  CalibrationOutcome outcome = run_calibration(data, calibration_settings(plan, "calibration"));
  wall.calibration = since(t);
  if (!outcome.converged)
    spdlog::warn(
        "the calibration did not converge; the pipeline goes on with its MAP point (see calibration/summary.txt)");
  return outcome;
}

SoilChoice scm_choice(const PipelinePlan& plan, const lowfi::ScmSoil& set) {
  SoilChoice scm;
  scm.solver = SoilModel::kScm;
  scm.scm = set;
  scm.gravity = plan.soil.gravity;
  return scm;
}

// The SCM (and Wong-Reece) wheels' options: with a set calibrated on the wheel, slip sinkage is on.
TerrainOptions scm_options(const PipelinePlan& plan) {
  TerrainOptions o = plan.terrain;
  o.grid = plan.scm_grid;
  o.step = 0;
  const std::string slip_sinkage = lowfi::ScmSlipSinkage::kName;
  if (plan.calibrate_on_wheel && std::find(o.scm_effects.begin(), o.scm_effects.end(), slip_sinkage) == o.scm_effects.end())
    o.scm_effects.push_back(slip_sinkage);
  return o;
}

// 3b. The SCM wheel on the calibrated set. A free-Kc set can fit the plates and still be negative
// (Kc/b + Kphi < 0) for the wheel's narrower contact patch, where SCM has no strength: then the set
// is calibrated again with Kc fixed at 0 (Bekker's law without the width term) into
// OUT/calibration_kc0/, and the report says so.
std::vector<rigs::WheelResult> scm_wheel_stage(const PipelinePlan& plan, const CalibrationData& data,
                                               PipelineResults& r) {
  SoilChoice scm = scm_choice(plan, r.calibration.fitted);
  r.wheel_set = r.calibration.fitted;
  r.wheel_posterior = r.calibration.posterior_sets;
  try {
    return run_wheel_sweep(SoilModel::kScm, scm, scm_options(plan), plan.wheel, plan.slips, plan.scm_wheel_run,
                           &r.scm_wheel_site);
  } catch (const lowfi::NoBekkerStrength& e) {
    spdlog::warn("{}", e.what());
    spdlog::warn("recalibrating with Kc fixed at 0 for the SCM wheel (calibration_kc0/)");
    r.scm_note = fmt::format(
        "The calibrated set (free Kc) could not drive the SCM wheel: {} The SCM wheel uses the set "
        "calibrated with Kc fixed at 0 (calibration_kc0/).",
        e.what());
    CalibrationData kc0 = data;
    kc0.priors[bayes::kKc] = bayes::fixed_prior(0);
    const CalibrationOutcome kc0_outcome = run_calibration(kc0, calibration_settings(plan, "calibration_kc0"));
    r.wheel_set = kc0_outcome.fitted;
    r.wheel_posterior = kc0_outcome.posterior_sets;
    scm.scm = r.wheel_set;
    return run_wheel_sweep(SoilModel::kScm, scm, scm_options(plan), plan.wheel, plan.slips, plan.scm_wheel_run,
                           &r.scm_wheel_site);
  }
}

// The CRM wheel sweep (before the calibration when the calibration uses it).
void crm_wheel_stage(const PipelinePlan& plan, const SoilChoice& crm, PipelineResults& r) {
  spdlog::info("pipeline: CRM single wheel, slips {}", fmt::join(plan.slips, ", "));
  const auto t = Clock::now();
  r.wheel_crm = run_wheel_sweep(SoilModel::kCrm, crm, plan.terrain, plan.wheel, plan.slips, plan.crm_wheel_run,
                                &r.crm_wheel_site);
  r.wall.crm_wheel = since(t);
  const std::string dir = plan.out + "/wheel_crm";
  std::filesystem::create_directories(dir);
  rigs::write_wheel_csv(dir + "/wheel.csv", r.wheel_crm);
  rigs::write_wheel_series_csv(dir + "/wheel_series.csv", r.wheel_crm);
}

// 3. The wheel sweeps: SCM on the calibrated set, and Wong-Reece on the set the SCM wheel used; the
// curves go to OUT/wheel_<model>/.
void wheel_stage(const PipelinePlan& plan, const CalibrationData& data, PipelineResults& r) {
  spdlog::info("pipeline 3/4: single wheel, slips {}: SCM (calibrated) and Wong-Reece", fmt::join(plan.slips, ", "));
  const auto t = Clock::now();
  r.wheel_scm = scm_wheel_stage(plan, data, r);
  r.wall.scm_wheel = since(t);
  r.wheel_wong_reece = run_wheel_sweep(SoilModel::kWongReece, scm_choice(plan, r.wheel_set), scm_options(plan),
                                       plan.wheel, plan.slips, plan.scm_wheel_run);
  for (const auto& [name, res] : {std::pair{"scm", &r.wheel_scm}, std::pair{"wong_reece", &r.wheel_wong_reece}}) {
    const std::string dir = plan.out + "/wheel_" + name;
    std::filesystem::create_directories(dir);
    rigs::write_wheel_csv(dir + "/wheel.csv", *res);
    if (std::string(name) != "wong_reece") rigs::write_wheel_series_csv(dir + "/wheel_series.csv", *res);
  }
  r.scm_band = scm_wheel_band(r.wheel_posterior, plan.wheel, plan.soil.gravity, plan.slips, plan.calibrate_on_wheel,
                              scm_options(plan), plan.scm_wheel_run);
  write_wheel_band_csv(plan.out + "/wheel_scm/band.csv", r.scm_band);
  plot_wheel_models(
      plan.out,
      {{"CRM", r.wheel_crm}, {"SCM (calibrated)", r.wheel_scm}, {"Wong-Reece (calibrated)", r.wheel_wong_reece}},
      &r.scm_band);
}
}  // namespace

std::vector<std::string> parse_check_rigs(const std::string& text) {
  if (text.empty()) return {};
  if (text == "all") return {"plate", "annulus", "wheel"};
  std::vector<std::string> rigs;
  std::size_t from = 0;
  while (from <= text.size()) {
    const std::size_t comma = std::min(text.find(',', from), text.size());
    const std::string rig = text.substr(from, comma - from);
    if (rig != "plate" && rig != "annulus" && rig != "wheel")
      throw InputError(fmt::format(
          "--checks '{}': '{}' is not a rig (expected all, or a comma list of plate, annulus, wheel)", text, rig));
    rigs.push_back(rig);
    from = comma + 1;
  }
  return rigs;
}

namespace {
// Every stage's values, and whether each run fits in memory, before OUT is made: a refusal leaves no
// folder behind and never comes after hours of CRM.
void check_pipeline(const PipelinePlan& plan, const SoilChoice& crm) {
  check_rig_gravity(plan.soil.gravity, plan.soil_name + ": key 'soil.gravity'");
  check_bevameter(crm, plan.terrain, plan.bevameter, true, true);
  check_wheel_sweep(SoilModel::kCrm, crm, plan.terrain, plan.wheel, plan.slips, plan.crm_wheel_run);
  check_wheel_sweep(SoilModel::kScm, scm_choice(plan, lowfi::ScmSoil{}), scm_options(plan), plan.wheel, plan.slips,
                    plan.scm_wheel_run);
  check_pipeline_checks(plan, crm);
  warn_about_sweep(plan.wheel, plan.slips);
  for (double s : plan.calibration_slips)
    if (std::find(plan.slips.begin(), plan.slips.end(), s) == plan.slips.end())
      throw InputError(fmt::format("--calibration-slips: slip {} is not among --slips ({}); expected a subset", s,
                                   fmt::join(plan.slips, ",")));
  if (!plan.calibration_slips.empty() && !plan.calibrate_on_wheel)
    throw InputError("--calibration-slips: only with --calibrate-on bevameter+wheel");
}
}  // namespace

int run_pipeline(const PipelinePlan& plan) {
  const auto start = Clock::now();
  SoilChoice crm;
  crm.solver = SoilModel::kCrm;
  crm.crm = plan.soil;
  crm.gravity = plan.soil.gravity;
  check_pipeline(plan, crm);
  std::filesystem::create_directories(plan.out);

  PipelineResults r;
  // The CRM bevameter and the CRM wheel sweep need nothing of each other: where CRM runs go at once
  // (a GPU), the wheel's small runs fill the gaps of the plates' large ones.
  r.wall.crm_at_once = crm_runs_go_at_once(plan.terrain);
  run_concurrently(2, r.wall.crm_at_once ? 2 : 1, [&](std::size_t stage) {
    if (stage == 0)
      r.bevameter = bevameter_stage(plan, crm, r.wall);
    else
      crm_wheel_stage(plan, crm, r);
  });
  CalibrationData data = calibration_data(r.bevameter, plan.out + "/bevameter");
  if (plan.calibrate_on_wheel)
    data.wheel = wheel_calibration_data(r.wheel_crm, plan.wheel, plan.out + "/wheel_crm/wheel.csv",
                                        plan.calibration_slips);
  r.calibration = calibration_stage(plan, data, r.wall);
  plot_bevameter(plan.out, r.bevameter, &r.calibration.fitted);
  wheel_stage(plan, data, r);
  if (!plan.checks.empty()) {
    spdlog::info("pipeline: bin-size and run-length checks");
    r.checks = run_checks(plan, crm, r.bevameter, r.wheel_crm);
  }
  spdlog::info("pipeline 4/4: report");
  r.wall.total = since(start);
  write_pipeline_report(plan, r);
  spdlog::info("pipeline done in {:.1f} s: {}/report.md", since(start), plan.out);
  return r.calibration.converged ? 0 : 1;
}

void replot_pipeline(const std::string& dir) {
  BevameterCurves c;
  const CsvTable plate = CsvTable::read(dir + "/bevameter/plate.csv");
  for (std::size_t i = 0; i < plate.rows(); ++i)
    c.plate.push_back({plate.number(i, "plate_radius_m"), plate.number(i, "sinkage_m"), plate.number(i, "force_N"),
                       plate.text(i, "phase")});
  const CsvTable shear = CsvTable::read(dir + "/bevameter/shear.csv");
  for (std::size_t i = 0; i < shear.rows(); ++i)
    c.shear.push_back({shear.number(i, "inner_radius_m"), shear.number(i, "outer_radius_m"),
                       shear.number(i, "normal_load_N"), shear.number(i, "angle_rad"), shear.number(i, "torque_Nm"),
                       0});
  const lowfi::ScmSoil fit = lowfi::read_scm_json(dir + "/calibration/scm_params.json");
  plot_bevameter(dir, c, &fit);
  auto wheel = [&](const std::string& name) {
    std::vector<rigs::WheelResult> out;
    const CsvTable t = CsvTable::read(dir + "/" + name + "/wheel.csv");
    for (std::size_t i = 0; i < t.rows(); ++i) {
      rigs::WheelResult r;
      r.slip = t.number(i, "slip");
      r.dbp = t.number(i, "dbp_N");
      r.torque = t.number(i, "torque_Nm");
      r.sinkage = t.number(i, "sinkage_m");
      out.push_back(r);
    }
    return out;
  };
  const std::string band_csv = dir + "/wheel_scm/band.csv";
  const WheelBand band = std::filesystem::exists(band_csv) ? read_wheel_band_csv(band_csv) : WheelBand{};
  plot_wheel_models(dir,
                    {{"CRM", wheel("wheel_crm")},
                     {"SCM (calibrated)", wheel("wheel_scm")},
                     {"Wong-Reece (calibrated)", wheel("wheel_wong_reece")}},
                    &band);
}

}  // namespace terracal::app
