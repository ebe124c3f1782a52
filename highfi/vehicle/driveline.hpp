#pragma once
// The full vehicle's powertrain and driveline as shafts, after Chrono::Vehicle's shafts templates:
// engine on the crank (its torque map times the throttle, plus losses), a torque converter between the
// crank and the gearbox input (the turbine), the gearbox as a speed ratio from the turbine to the
// driveshaft (final drive included, so the differentials' ratio is one), a central differential to
// the front and rear driveshafts (four-wheel drive), an open differential per driven axle to its two
// axle shafts, each tied to its spindle's spin on the upright. Brakes act between spindle and upright
// as dry friction. The engine maps, converter and shift speeds are those of core/vehicle/powertrain.hpp,
// shared with the reduced-order vehicles.
#include <functional>
#include <vector>

#include "core/vehicle/driver_inputs.hpp"
#include "core/vehicle/powertrain.hpp"
#include "highfi/vehicle/double_wishbone.hpp"

namespace terracal::vehicle {

struct DrivelineSpec {
  double turbine_inertia = 0.3;          // the gearbox input shaft, kg m^2
  double driveshaft_inertia = 0.5;       // behind the gearbox
  double axle_driveshaft_inertia = 1.1;  // front and rear driveshafts with their differential boxes
};

struct Driveline {
  int crank = -1, turbine = -1, driveshaft = -1;
  std::vector<int> axle_driveshafts;  // per axle (-1: not driven)
  std::vector<int> axle_shafts;       // per wheel, in the corners' order
  int gearbox = -1;                   // the gearbox's coupling (its ratio changes with the gear)
  int gear = 0;
};

using DriverFunction = std::function<DriverInput(double t)>;

// Builds the driveline for `corners` (two per axle, left then right; axle_inertias per axle) and adds
// the engine, converter and brakes, driven by `driver`.
Driveline build_driveline(mb::MbSystem& s, const PowertrainParams& p, const DrivelineSpec& spec,
                          const std::vector<WishboneSide>& corners, const std::vector<double>& axle_inertias,
                          const DriverFunction* driver);

// Shifts by the gearbox input's speed (core/vehicle/powertrain.hpp, shift_gear); true when the gear
// changed (the caller then restarts its integrator from the new constraint).
// Puts the gearbox in `gear` (its coupling's ratio), the shafts' speeds left as they are.
void set_gear(mb::MbSystem& s, const PowertrainParams& p, Driveline& d, int gear);
bool update_gear(mb::MbSystem& s, const PowertrainParams& p, Driveline& d);

}  // namespace terracal::vehicle
