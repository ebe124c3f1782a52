// `terracal pipeline`: soil -> CRM bevameter -> calibrated SCM set -> single-wheel validation (CRM,
// SCM, Wong-Reece) -> report (docs/architecture.md, "The data path").
#include <map>
#include <memory>

#include <fmt/format.h>

#include "apps/bevameter_options.hpp"
#include "apps/calibration_run.hpp"
#include "apps/cli_checks.hpp"
#include "apps/commands.hpp"
#include "apps/out_dir.hpp"
#include "apps/pipeline.hpp"
#include "core/errors.hpp"

namespace terracal::app {

namespace {
struct PipelineArgs {
  std::string out, wheel, slips = kDefaultSlips, calibration_slips;
  bool calibrate_on_wheel = true;
  bayes::AnnulusLaw annulus_law = bayes::AnnulusLaw::kShared;
  double elastic_stiffness = 0;
  double wheel_duration = 3.0;
  std::uint64_t seed = 1;
  std::string checks;  // "" = none, "all", or a comma list of plate, annulus, wheel
  int check_realisations = 1;
  bool replot = false;
  TerrainOptions terrain;
  BevameterPlan plan;  // the plates and the annulus (apps/bevameter_options.hpp)
  // The annulus under 25 ... 200 kg dead loads in Earth's gravity.
  BevameterLists lists{"0.2,0.3", "0.15,0.20", "245.25,490.5,735.75,981,1226.25,1471.5,1716.75,1962"};
};
}  // namespace

Command add_pipeline(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "pipeline",
      "Soil -> CRM bevameter -> calibrated SCM set -> single-wheel validation (CRM, SCM, Wong-Reece) -> report");
  auto a = std::make_shared<PipelineArgs>();
  auto* soil = add_crm_terrain_options(sub, a->terrain);
  add_scm_grid_option(sub, a->terrain);
  add_step_option(sub, a->terrain);
  sub->add_option("--out", a->out, "output folder")->required();
  auto* replot = sub->add_flag("--replot", a->replot, "only draw the plots of the finished pipeline in --out again");
  soil->excludes(replot);
  sub->add_option("--wheel", a->wheel, "wheel file (JSON); default radius 0.47 m, width 0.25 m, 108 kg, 1 rad/s");
  sub->add_option("--slips", a->slips, "slips of the wheel sweep")
      ->check(list_in_range(rigs::WheelRanges::kSlip))
      ->capture_default_str();
  const std::map<std::string, bool> calibrate_on{{"bevameter", false}, {"bevameter+wheel", true}};
  add_choice(sub, "--calibrate-on", a->calibrate_on_wheel, calibrate_on,
             "curves the SCM set is fitted to: bevameter, or bevameter+wheel (the CRM wheel too, fitting slip "
             "sinkage; default)")
      ->default_str("bevameter+wheel");
  const std::map<std::string, bayes::AnnulusLaw> annulus_laws{{"shared", bayes::AnnulusLaw::kShared},
                                                              {"scaled", bayes::AnnulusLaw::kScaled}};
  auto* annulus_law =
      add_choice(sub, "--annulus-law", a->annulus_law, annulus_laws,
                 "with bevameter+wheel: shared (the annulus follows the set's c, phi, k) or scaled (the annulus's "
                 "strength is the set's over a fitted ratio, with its own Janosi k: the CRM wheel fits 2-3x better, "
                 "the chains need about 3x the draws)")
          ->default_str("shared");
  sub->add_option("--elastic-stiffness", a->elastic_stiffness,
                  "the set's SCM elastic stiffness [Pa/m], as calibrate --elastic-stiffness; 0: fitted to the plates' "
                  "unload rows")
      ->check(off_or_in_range(CalibrationRanges::kElasticStiffness))
      ->capture_default_str();
  sub->add_option("--calibration-slips", a->calibration_slips,
                  "with bevameter+wheel: the CRM wheel's slips the calibration sees (default all of --slips); the "
                  "others are held out")
      ->check(list_in_range(rigs::WheelRanges::kSlip));
  sub->add_option("--wheel-duration", a->wheel_duration, "simulated seconds per slip")
      ->check(in_range(rigs::WheelRanges::kDuration))
      ->capture_default_str();
  add_seed_option(sub, a->seed, "calibration seed");
  sub->add_flag("--checks{all}", a->checks,
                "rerun the rigs (all, or a list such as annulus,wheel) in a 1.5x bin and 1.5x longer; default off");
  sub->add_option("--check-realisations", a->check_realisations,
                  "beds per bin whose means the annulus and wheel bin checks compare (docs/decisions.md)")
      ->transform(whole_in(1, kMaxCheckRealisations))
      ->capture_default_str();
  add_bevameter_options(sub, a->plan, a->lists);
  return [a, annulus_law] {
    const OutDir out = prepare_out_dir("--out", a->out);
    if (a->replot) {
      replot_pipeline(a->out);
      return 0;
    }
    if (a->terrain.soil_json.empty()) throw InputError("--soil: required (the CRM soil material, JSON)");
    PipelinePlan p;
    p.bevameter = a->plan;
    p.soil = load_crm_soil(a->terrain.soil_json);
    p.soil_name = a->terrain.soil_json;
    p.terrain = a->terrain;
    p.out = a->out;
    p.seed = a->seed;
    p.checks = parse_check_rigs(a->checks);
    p.check_realisations = a->check_realisations;
    if (a->terrain.settle_seed > (1L << 62) - (a->check_realisations - 1))
      throw InputError(
          fmt::format("--settle-seed {}: the realisations use seeds up to {} more; expected at most 2^62 - {}",
                      a->terrain.settle_seed, a->check_realisations - 1, a->check_realisations - 1));
    p.scm_grid = a->terrain.grid;
    p.slips = parse_list(a->slips, "--slips");
    p.calibrate_on_wheel = a->calibrate_on_wheel;
    p.annulus_law = a->annulus_law;
    p.elastic_stiffness = a->elastic_stiffness;
    if (annulus_law->count() > 0 && !p.calibrate_on_wheel)
      throw InputError("--annulus-law: only with --calibrate-on bevameter+wheel (the bevameter alone has one law)");
    if (!a->calibration_slips.empty()) p.calibration_slips = parse_list(a->calibration_slips, "--calibration-slips");
    apply_bevameter_lists(a->lists, p.bevameter);
    if (!a->wheel.empty()) p.wheel = rigs::read_wheel_json(a->wheel);
    p.crm_wheel_run.duration = p.scm_wheel_run.duration = a->wheel_duration;
    rigs::validate(p.crm_wheel_run);
    return run_pipeline(p);
  };
}

}  // namespace terracal::app
