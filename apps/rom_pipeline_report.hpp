#pragma once
// pipeline-rom's report: report.md (the runs, the calibrated parameters, the validation, the
// accuracy-cost table and the wall time per stage), summary.json, accuracy_cost.csv and the
// accuracy-cost plot.
#include "apps/rom_calibration.hpp"
#include "apps/rom_pipeline.hpp"
#include "apps/rom_validation.hpp"

namespace terracal::app {

void write_rom_pipeline_report(const RomPipelineSettings& s, const RomPipelineOutcome& o,
                               const RomCalibrationOutcome& calibration, const RomValidationOutcome& validation);

}  // namespace terracal::app
