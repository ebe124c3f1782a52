#pragma once
// The HMMWV's front double-wishbone suspension (Chrono's HMMWV_DoubleWishboneFront.json in our format),
// as the built-in full HMMWV carries it.
#include <nlohmann/json.hpp>

#include "highfi/vehicle/full_vehicle.hpp"

namespace terracal::test {

inline nlohmann::json hmmwv_front_suspension_json() {
  return nlohmann::json::parse(vehicle::full_vehicle_preset_json("hmmwv"))["axles"][0]["suspension"];
}

}  // namespace terracal::test
