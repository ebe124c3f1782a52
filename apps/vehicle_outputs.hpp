#pragma once
// The files of one full-vehicle run, as `terracal vehicle` writes them and `pipeline-rom` reuses:
// trajectory.csv, wheels.csv, inputs.txt (the driver inputs applied, as a driver file) and run.json;
// and what a manoeuvre needs to know of the full vehicle.
#include <string>

#include "core/vehicle/maneuver.hpp"
#include "highfi/vehicle/vehicle_run.hpp"

namespace terracal::app {

struct VehicleRunInfo {
  std::string vehicle, terrain, scm;  // as given (run.json)
  std::string driver;                 // the manoeuvre or driver file (inputs.txt's header)
  bool from_inputs = false;           // driven by a driver file, not a manoeuvre
  bool vtu = false;                   // snapshots were written (run.json lists them)
};

void write_vehicle_outputs(const std::string& out, const VehicleRunInfo& info, const vehicle::VehicleRunOptions& run,
                           const vehicle::VehicleRunResult& r);

// The wheelbase, the road-wheel angle at full steering (the mean of the two steered wheels' at full
// lock to the left, kinematic) and the track; InputError for a vehicle without steering.
ManeuverVehicle maneuver_vehicle(const vehicle::FullVehicleSpec& spec);

}  // namespace terracal::app
