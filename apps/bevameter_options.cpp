#include "apps/bevameter_options.hpp"

#include <fmt/format.h>

#include "apps/terrain_options.hpp"
#include "core/errors.hpp"

namespace terracal::app {

namespace {
void add_plate_options(CLI::App* sub, BevameterPlan& plan, BevameterLists& lists) {
  const BevameterPlan checked;
  sub->add_option("--plates", lists.plates, "plate radii [m], comma-separated")->capture_default_str();
  sub->add_option("--max-sinkage", plan.max_sinkage, "plate sinkage at the end of the stroke [m]")
      ->capture_default_str();
  sub->add_option("--plate-speed", plan.plate_speed, "plate speed [m/s]")->capture_default_str();
  sub->add_option("--plate-spacing", plan.plate_spacing, "CRM particle spacing of the plate runs [m] (0: as --spacing)")
      ->capture_default_str();
  sub->add_option("--plate-wall-radii", plan.plate_wall_radii,
                  fmt::format("CRM plate bin: walls this many plate radii from the centre (checked: {})",
                              checked.plate_wall_radii))
      ->capture_default_str();
  sub->add_option("--plate-depth-scale", plan.plate_depth_scale,
                  fmt::format("CRM plate bin: soil depth = this x (max sinkage + 2.5 radii) (checked: {})",
                              checked.plate_depth_scale))
      ->capture_default_str();
}

void add_shear_options(CLI::App* sub, BevameterPlan& plan, BevameterLists& lists) {
  sub->add_option("--annulus", lists.annulus, "annulus inner,outer radius [m]")->capture_default_str();
  auto* loads =
      sub->add_option("--shear-loads", lists.shear_loads, "annulus normal loads [N], comma-separated, each > 0");
  if (!lists.shear_loads.empty()) loads->capture_default_str();
  sub->add_option("--shear-angle", plan.shear_angle, "angle the annulus turns [rad]")->capture_default_str();
  sub->add_option("--shear-rate", plan.shear_rate, "annulus angular velocity [rad/s]")->capture_default_str();
  sub->add_option("--shear-settle", plan.shear_settle, "annulus settling under its load before turning [s]")
      ->capture_default_str();
  sub->add_option(
         "--shear-load-ramp", plan.shear_load_ramp,
         "fraction of --shear-settle over which the annulus's load grows from zero, 0 ... 1 (0: dropped at once)")
      ->capture_default_str();
  sub->add_option("--shear-step", plan.shear_step, "CRM time step of the annulus runs [s] (0: as --step)")
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
  if (lists.shear_loads.empty()) return;
  for (double load : parse_list(lists.shear_loads, "--shear-loads")) {
    if (!(load > 0)) throw InputError(fmt::format("--shear-loads: {} N; expected > 0", load));
    plan.shear_loads.push_back(load);
  }
}

}  // namespace terracal::app
