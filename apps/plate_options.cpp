#include "apps/plate_options.hpp"

#include <fmt/format.h>

namespace terracal::app {

void add_plate_options(CLI::App* sub, BevameterPlan& plan) {
  sub->add_option("--plate-speed", plan.plate_speed, "plate speed [m/s]")->capture_default_str();
  sub->add_option("--plate-spacing", plan.plate_spacing, "CRM particle spacing of the plate runs [m] (0: as --spacing)")->capture_default_str();
  sub->add_option("--plate-wall-radii", plan.plate_wall_radii,
                  fmt::format("CRM plate bin: walls this many plate radii from the centre (checked: {})", BevameterPlan{}.plate_wall_radii))
      ->capture_default_str();
  sub->add_option("--plate-depth-scale", plan.plate_depth_scale,
                  fmt::format("CRM plate bin: soil depth = this x (max sinkage + 2.5 radii) (checked: {})", BevameterPlan{}.plate_depth_scale))
      ->capture_default_str();
}

}  // namespace terracal::app
