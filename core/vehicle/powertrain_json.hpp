#pragma once
// The powertrain object of a vehicle file (docs/formats.md, "ROM vehicle", key `powertrain`), read and
// checked once for every vehicle model that has one (the reduced-order vehicles and the full one).
// Engine maps in rpm as Chrono's, stored in rad/s.
#include "core/json_object.hpp"
#include "core/vehicle/powertrain.hpp"

namespace terracal {

// Reads `powertrain` (every key checked; an unknown key is an error).
PowertrainParams read_powertrain(JsonObject pt);
// The checks across keys: gear ratios increase, each gear's downshift speed is below its upshift
// speed, the converter's torque ratio does not rise. `source` names the input in messages.
void validate_powertrain(const PowertrainParams& p, const std::string& source);

}  // namespace terracal
