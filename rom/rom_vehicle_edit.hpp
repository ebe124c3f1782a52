#pragma once
// A vehicle file with parameter values put in: what apply_vary_parameter does to a RomVehicle,
// done to the file's JSON, so that a calibrated vehicle is written as a vehicle file that loads as
// --vehicle (with the keys it had, and the tires split into tire_front and tire_rear when a
// parameter acts on one axle's tires).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace terracal::rom {

// `name_or_path`: a preset (hmmwv, sedan) or a vehicle file in terracal's format (a tire given as a
// file name is read into the result). Throws InputError for an LFDM vehicle file (its keys differ:
// write it in terracal's format first), an unknown parameter, or one a vehicle file does not hold
// (friction, gravity: run settings).
nlohmann::ordered_json vehicle_json_with(const std::string& name_or_path, const std::vector<std::string>& names,
                                         const std::vector<double>& values);

// Parameters vehicle_json_with cannot write (they are not in a vehicle file).
bool is_run_setting(const std::string& name);

}  // namespace terracal::rom
