#pragma once
// Reduced-order vehicles from JSON (docs/formats.md, "ROM vehicle"): our own keys, or an LFDM
// vehicle file (uwsbel/low-fidelity-dynamic-models, data/json/*/vehicle.json) where the meaning is
// the same; the presets `hmmwv` and `sedan` are built in. Every value is validated; a bad file is an
// InputError naming the file, the key, the value and the allowed range.
#include <string>

#include <nlohmann/json.hpp>

#include "core/json_object.hpp"
#include "rom/rom_vehicle.hpp"

namespace terracal::rom {

// `source` names the input in messages. A "tire" given as a string is a tire file's path, read
// relative to `folder` when not absolute. `tire`: replaces the vehicle's tires (an LFDM vehicle
// file has none of its own and needs one).
RomVehicle read_rom_vehicle(const nlohmann::json& j, const std::string& source, const std::string& folder = ".",
                            const TmeasyParams* tire = nullptr);
// The vehicle part of an LFDM vehicle file (rom_vehicle_lfdm.cpp); the tires are left empty.
RomVehicle read_lfdm_vehicle(JsonObject& o);
// A preset name (hmmwv, sedan) or a vehicle file's path.
RomVehicle load_rom_vehicle(const std::string& name_or_path, const std::string& tire_override = "");
// The preset's JSON text (embedded), or "" for an unknown name.
std::string rom_preset_json(const std::string& name);

// The checks every vehicle passes, however it was built (also after a --vary draw).
void validate(const RomVehicle& v, const std::string& source);

}  // namespace terracal::rom
