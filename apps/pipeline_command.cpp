// `terracal pipeline`: soil -> CRM bevameter -> calibrated SCM set -> single-wheel validation (CRM,
// SCM, Wong-Reece) -> report. DESIGN.md section 3.
#include <memory>

#include <fmt/format.h>

#include "apps/commands.hpp"
#include "apps/pipeline.hpp"
#include "apps/plate_options.hpp"
#include "core/errors.hpp"

namespace terracal::app {

namespace {
struct PipelineArgs {
  std::string soil, out, wheel, slips = "0,0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8", plates = "0.2,0.3", annulus = "0.15,0.20";
  std::string loads_kg = "25,50,75,100,125,150,175,200";
  double max_sinkage = 0.2, wheel_duration = 3.0, shear_step = 0, shear_angle = 1.0, shear_settle = 1.0, shear_load_ramp = 0.5;
  std::uint64_t seed = 1;
  std::string checks;  // "" = none, "all", or a comma list of plate, annulus, wheel
  int check_realisations = 1;
  bool replot = false;
  TerrainOptions terrain;
  BevameterPlan plate;  // plate speed and CRM bin (apps/plate_options.hpp)
};
}  // namespace

Command add_pipeline(CLI::App& app) {
  auto* sub = app.add_subcommand("pipeline", "Soil -> CRM bevameter -> calibrated SCM set -> single-wheel validation (CRM, SCM, Wong-Reece) -> report");
  auto a = std::make_shared<PipelineArgs>();
  auto* soil = sub->add_option("--soil", a->terrain.soil_json, "CRM soil material (JSON, DESIGN.md 'Soil')");
  sub->add_option("--out", a->out, "output folder")->required();
  auto* replot = sub->add_flag("--replot", a->replot, "only draw the plots of the finished pipeline in --out again");
  soil->excludes(replot);
  sub->add_option("--wheel", a->wheel, "wheel file (JSON); default radius 0.47 m, width 0.25 m, 108 kg, 1 rad/s");
  sub->add_option("--slips", a->slips, "slips of the wheel sweep")->capture_default_str();
  sub->add_option("--plates", a->plates, "plate radii [m]")->capture_default_str();
  sub->add_option("--max-sinkage", a->max_sinkage, "plate sinkage [m]")->capture_default_str();
  sub->add_option("--annulus", a->annulus, "annulus inner,outer radius [m]")->capture_default_str();
  sub->add_option("--shear-loads-kg", a->loads_kg, "annulus dead loads [kg]")->capture_default_str();
  sub->add_option("--wheel-duration", a->wheel_duration, "simulated seconds per slip")->capture_default_str();
  sub->add_option("--seed", a->seed, "calibration seed")->capture_default_str();
  sub->add_flag("--checks{all}", a->checks,
                "rerun each rig in a 1.5x bin and 1.5x longer (bin-size and run-length checks); --checks=annulus,wheel for some rigs only");
  sub->add_option("--check-realisations", a->check_realisations,
                  "bin checks of the annulus and the wheel: compare the means of this many runs per bin (the base run, and runs whose "
                  "bed settled from a start jittered by 0.1 spacings with seeds --settle-seed + 1, + 2, ...); 1 ... 16")
      ->capture_default_str();
  sub->add_option("--spacing", a->terrain.spacing, "CRM particle spacing [m]")->capture_default_str();
  add_device_option(sub, a->terrain.device);
  sub->add_option("--cache", a->terrain.cache, "folder of settled CRM beds")->capture_default_str();
  sub->add_option("--grid", a->terrain.grid, "SCM grid [m]")->capture_default_str();
  sub->add_option("--step", a->terrain.step, "CRM time step [s] (0: from the CFL limit)")->capture_default_str();
  sub->add_option("--shear-angle", a->shear_angle, "angle the annulus turns [rad]")->capture_default_str();
  sub->add_option("--shear-settle", a->shear_settle, "annulus settling under its load before turning [s]")->capture_default_str();
  sub->add_option("--shear-load-ramp", a->shear_load_ramp,
                  "the annulus's load grows from zero over this fraction of --shear-settle, as a bevameter's ram puts it on "
                  "(0: dropped at once, which leaves the ring moving, differently in each bin, when it starts to turn; "
                  "results/plate_bin_check, twelfth study); 0 ... 1")
      ->capture_default_str();
  sub->add_option("--shear-step", a->shear_step, "CRM time step of the annulus runs [s] (0: as --step)")->capture_default_str();
  add_crm_settling_options(sub, a->terrain);
  add_plate_options(sub, a->plate);
  return [a] {
    if (a->replot) {
      replot_pipeline(a->out);
      return 0;
    }
    if (a->terrain.soil_json.empty()) throw InputError("--soil: required (the CRM soil material, JSON)");
    PipelinePlan p;
    p.bevameter = a->plate;
    p.soil = load_crm_soil(a->terrain.soil_json);
    p.soil_name = a->terrain.soil_json;
    p.terrain = a->terrain;
    p.out = a->out;
    p.seed = a->seed;
    p.checks = parse_check_rigs(a->checks);
    if (!(a->check_realisations >= 1 && a->check_realisations <= 16))
      throw InputError(fmt::format("--check-realisations {}: expected an integer in [1, 16]", a->check_realisations));
    p.check_realisations = a->check_realisations;
    if (a->terrain.settle_seed > (1L << 62) - (a->check_realisations - 1))
      throw InputError(fmt::format("--settle-seed {}: the realisations use seeds up to {} more; expected at most 2^62 - {}", a->terrain.settle_seed,
                                   a->check_realisations - 1, a->check_realisations - 1));
    p.scm_grid = a->terrain.grid;
    p.slips = parse_list(a->slips, "--slips");
    p.bevameter.plates = parse_list(a->plates, "--plates");
    p.bevameter.max_sinkage = a->max_sinkage;
    p.bevameter.shear_step = a->shear_step;
    p.bevameter.shear_angle = a->shear_angle;
    p.bevameter.shear_settle = a->shear_settle;
    p.bevameter.shear_load_ramp = a->shear_load_ramp;
    const auto ann = parse_list(a->annulus, "--annulus");
    if (ann.size() != 2) throw InputError(fmt::format("--annulus '{}': expected INNER,OUTER", a->annulus));
    p.bevameter.inner_radius = ann[0];
    p.bevameter.outer_radius = ann[1];
    for (double kg : parse_list(a->loads_kg, "--shear-loads-kg")) {
      if (!(kg > 0)) throw InputError(fmt::format("--shear-loads-kg: {} kg; expected > 0", kg));
      p.bevameter.shear_loads.push_back(kg * norm(p.soil.gravity));
    }
    if (!a->wheel.empty()) p.wheel = rigs::read_wheel_json(a->wheel);
    p.crm_wheel_run.duration = p.scm_wheel_run.duration = a->wheel_duration;
    rigs::validate(p.crm_wheel_run);
    return run_pipeline(p);
  };
}

}  // namespace terracal::app
