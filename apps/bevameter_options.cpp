#include "apps/bevameter_options.hpp"

#include <fmt/format.h>

#include "apps/cli_checks.hpp"
#include "apps/terrain_options.hpp"
#include "core/errors.hpp"

namespace terracal::app {

namespace {
using R = BevameterRanges;

void add_plate_options(CLI::App* sub, BevameterPlan& plan, BevameterLists& lists) {
  const BevameterPlan checked;
  sub->add_option("--plates", lists.plates, "plate radii [m], comma-separated")
      ->check(list_in_range(R::kPlateRadius))
      ->capture_default_str();
  sub->add_option("--max-sinkage", plan.max_sinkage, "plate sinkage at the end of the stroke [m] (<= 5 plate radii)")
      ->check(in_range(R::kMaxSinkage))
      ->capture_default_str();
  sub->add_option("--plate-speed", plan.plate_speed, "plate speed [m/s]")
      ->check(in_range(R::kPlateSpeed))
      ->capture_default_str();
  sub->add_option("--plate-unload-speed", plan.plate_unload_speed,
                  "plate speed of the unload-reload cycle [m/s] (0: as --plate-speed)")
      ->check(off_or_in_range(R::kPlateSpeed))
      ->capture_default_str();
  sub->add_option("--plate-spacing", plan.plate_spacing, "CRM particle spacing of the plate runs [m] (0: as --spacing)")
      ->check(off_or_in_range(RigRanges::kSpacing))
      ->capture_default_str();
  sub->add_option("--plate-wall-radii", plan.plate_wall_radii,
                  fmt::format("CRM plate bin: walls this many plate radii from the centre (checked: {})",
                              checked.plate_wall_radii))
      ->check(in_range(R::kPlateWallRadii))
      ->capture_default_str();
  sub->add_option("--plate-depth-scale", plan.plate_depth_scale,
                  fmt::format("CRM plate bin: soil depth = this x (max sinkage + 2.5 radii) (checked: {})",
                              checked.plate_depth_scale))
      ->check(in_range(R::kPlateDepthScale))
      ->capture_default_str();
}

void add_shear_options(CLI::App* sub, BevameterPlan& plan, BevameterLists& lists) {
  sub->add_option("--annulus", lists.annulus, "annulus inner,outer radius [m]")
      ->check(list_in_range(R::kAnnulusRadius))
      ->capture_default_str();
  auto* loads = sub->add_option("--shear-loads", lists.shear_loads, "annulus normal loads [N], comma-separated")
                    ->check(list_in_range(R::kShearLoad));
  if (!lists.shear_loads.empty()) loads->capture_default_str();
  sub->add_option("--shear-angle", plan.shear_angle, "angle the annulus turns [rad]")
      ->check(in_range(R::kShearAngle))
      ->capture_default_str();
  sub->add_option("--shear-rate", plan.shear_rate, "annulus angular velocity [rad/s]")
      ->check(in_range(R::kShearRate))
      ->capture_default_str();
  sub->add_option("--shear-settle", plan.shear_settle, "annulus settling under its load before turning [s]")
      ->check(in_range(R::kShearSettle))
      ->capture_default_str();
  sub->add_option("--shear-load-ramp", plan.shear_load_ramp,
                  "fraction of --shear-settle over which the annulus's load grows from zero (0: dropped at once)")
      ->check(in_range(R::kShearLoadRamp))
      ->capture_default_str();
  sub->add_option("--shear-step", plan.shear_step, "CRM time step of the annulus runs [s] (0: as --step)")
      ->check(in_range(RigRanges::kStep))
      ->capture_default_str();
}
}  // namespace

void add_bevameter_options(CLI::App* sub, BevameterPlan& plan, BevameterLists& lists) {
  add_plate_options(sub, plan, lists);
  add_shear_options(sub, plan, lists);
}

void apply_bevameter_lists(const BevameterLists& lists, BevameterPlan& plan) {
  plan.plates = parse_list(lists.plates, "--plates");
  const auto annulus = parse_list(lists.annulus, "--annulus");
  if (annulus.size() != 2)
    throw InputError(fmt::format("--annulus '{}': expected two radii INNER,OUTER", lists.annulus));
  plan.inner_radius = annulus[0];
  plan.outer_radius = annulus[1];
  plan.shear_loads.clear();
  if (!lists.shear_loads.empty()) plan.shear_loads = parse_list(lists.shear_loads, "--shear-loads");
}

}  // namespace terracal::app
