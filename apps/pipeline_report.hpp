#pragma once
// What `pipeline` found, and the report it writes of it: OUT/report.md (Markdown with the plots, the
// calibrated set, the wheel table, the errors against CRM, the checks and the cost) and
// OUT/summary.json (the same figures for scripts; docs/formats.md).
#include <string>
#include <vector>

#include "apps/calibration_run.hpp"
#include "apps/wheel_band.hpp"
#include "apps/pipeline.hpp"
#include "apps/pipeline_checks.hpp"

namespace terracal::app {

// Wall seconds of each stage.
struct StageTimes {
  double bevameter = 0, calibration = 0, crm_wheel = 0, scm_wheel = 0, total = 0;
  bool crm_at_once = false;  // the CRM bevameter and wheel sweep ran at once (their times overlap)
};

struct PipelineResults {
  BevameterCurves bevameter;
  CalibrationOutcome calibration;  // on the CRM curves, Kc free
  lowfi::ScmSoil wheel_set;        // the set the SCM and Wong-Reece wheels ran on
  std::string scm_note;            // why that is not the calibrated set, if it is not
  std::vector<rigs::WheelResult> wheel_crm, wheel_scm, wheel_wong_reece;
  std::vector<lowfi::ScmSoil> wheel_posterior;  // posterior sets of the calibration the SCM wheel used
  WheelBand scm_band;                           // those sets through the steady SCM wheel
  std::string crm_wheel_site, scm_wheel_site;
  std::vector<PipelineCheck> checks;
  StageTimes wall;
};

void write_pipeline_report(const PipelinePlan& plan, const PipelineResults& results);

}  // namespace terracal::app
