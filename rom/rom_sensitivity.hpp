#pragma once
// Forward sensitivities of a CVODES run (the calibrator's gradients): d(state)/d(parameter) at every
// output sample, for chosen vehicle parameters, by CVODES's staggered corrector with difference
// quotients of the right-hand side. Gear shifts restart the solver; the jump a shift would put into
// the sensitivities is neglected (a shift time's dependence on the parameters).
#include <string>
#include <vector>

#include "core/vehicle/driver_inputs.hpp"
#include "rom/rom_run.hpp"
#include "rom/rom_vehicle.hpp"

namespace terracal::rom {

// The parameters sensitivities can be taken with respect to (fields of RomVehicle).
const std::vector<std::string>& sensitivity_parameter_names();

struct RomSensitivityResult {
  std::vector<RomSample> samples;
  int states = 0;
  std::vector<std::string> parameters;
  // [sample][parameter][state]: d state / d parameter, states in the model's layout (docs/rom.md).
  std::vector<double> dstate_dparam;
  double at(std::size_t sample, int parameter, int state) const {
    return dstate_dparam[(sample * parameters.size() + parameter) * states + state];
  }
};

// Throws InputError for an unknown parameter name.
RomSensitivityResult run_rom_sensitivities(const RomVehicle& vehicle, const DriverSeries& driver,
                                           const RomRunOptions& options, const std::vector<std::string>& parameters);

}  // namespace terracal::rom
