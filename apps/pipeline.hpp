#pragma once
// The whole loop: a CRM soil -> CRM bevameter (plates, annulus) -> calibrated SCM set -> single-wheel
// slip sweeps in CRM, in SCM with the calibrated set, and with Wong-Reece -> a Markdown report with
// plots and an error table (apps/pipeline_report.hpp). `terracal pipeline` and `terracal demo` run it;
// docs/architecture.md walks through the stages.
#include <string>
#include <vector>

#include "apps/rig_runs.hpp"
#include "bayes/calibration_problem.hpp"

namespace terracal::app {

struct PipelinePlan {
  CrmSoil soil;
  std::string soil_name = "soil";
  TerrainOptions terrain;  // CRM spacing, device, cache; SCM grid and effects
  BevameterPlan bevameter;
  rigs::WheelSpec wheel;
  std::vector<double> slips;  // of the wheel sweeps (the commands default to kDefaultSlips)
  // Calibrate on the bevameter curves and the CRM wheel's (then the SCM and Wong-Reece wheels run
  // with slip sinkage, whose S the wheel fits), or on the bevameter curves alone.
  bool calibrate_on_wheel = true;
  // The CRM wheel's slips the calibration sees (a subset of `slips`; empty: all of them). The others
  // are held out: the report gives the error on them apart.
  std::vector<double> calibration_slips;
  // With the wheel in the calibration: the annulus's law shared with the set, or scaled by a fitted
  // strength ratio with its own Janosi k (CRM's annulus and wheel mobilise different strengths;
  // docs/decisions.md, "Annulus law").
  bayes::AnnulusLaw annulus_law = bayes::AnnulusLaw::kShared;
  double elastic_stiffness = 0;  // the set's Ke [Pa/m], as `calibrate --elastic-stiffness`; 0: the plates' fit
  rigs::WheelRun crm_wheel_run, scm_wheel_run;
  double scm_grid = 0.01;
  std::uint64_t seed = 1;
  // Rigs rerun in a 1.5x bin and for a 1.5x longer run (the bin-size and run-length checks), of
  // "plate", "annulus", "wheel"; empty = no checks.
  std::vector<std::string> checks;
  // Realisations per bin in the annulus's and the wheel's bin checks (1 ... 16): the base run, and
  // check_realisations - 1 more whose bed settled from a start jittered off the lattice with another
  // seed (pipeline_checks.cpp, realisation()); the check compares the means. Single CRM runs of the
  // thin annulus scatter by about as much as the bin moves them (results/plate_bin_check).
  int check_realisations = 1;
  std::string out;
};
inline constexpr int kMaxCheckRealisations = 16;

// "" -> no checks, "all" -> every rig, else a comma list of plate, annulus, wheel (InputError
// naming --checks otherwise).
std::vector<std::string> parse_check_rigs(const std::string& text);

// Returns 0, or 1 when the calibration did not converge (everything is still written).
int run_pipeline(const PipelinePlan& plan);

// Draws a finished pipeline's bevameter.png and wheel.png again from its CSV and JSON files (for
// runs made where gnuplot was missing, such as a GPU machine).
void replot_pipeline(const std::string& dir);

}  // namespace terracal::app
