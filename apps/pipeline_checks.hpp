#pragma once
// The pipeline's bin-size and run-length checks: each reruns one rig (plate, annulus, wheel) in a bin
// 1.5x larger and for a 1.5x longer run, and measures how far its curve moves
// (docs/decisions.md, "Bin-size and run-length checks").
#include <string>
#include <vector>

#include "apps/pipeline.hpp"

namespace terracal::app {

struct PipelineCheck {
  std::string rig, what;
  double change;
  bool bounded = true;  // a bin-size or run-length check (5 % bound); false: a measurement reported beside them
};

// Whether the runs of plan.checks fit in memory, and their values, checked before the pipeline starts.
void check_pipeline_checks(const PipelinePlan& plan, const SoilChoice& crm);

// The checks of plan.checks against the base runs; the rerun curves go to OUT/checks/.
std::vector<PipelineCheck> run_checks(const PipelinePlan& plan, const SoilChoice& crm, const BevameterCurves& base_bev,
                                      const std::vector<rigs::WheelResult>& base_wheel);

}  // namespace terracal::app
