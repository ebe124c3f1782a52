#pragma once
// The HMMWV preset with a rack-and-pinion steering in place of its Pitman arm: the rack where the
// Pitman arm's link is (the tie rods' inner points unchanged), Chrono's HMMWV rack data (9.07 kg,
// pinion radius 0.1 m, largest pinion angle 0.87 rad); the rack slides to the right (-y) to steer left.
#include <nlohmann/json.hpp>

#include "highfi/vehicle/full_vehicle.hpp"

namespace terracal::test {

inline nlohmann::json hmmwv_rack_json() {
  nlohmann::json j = nlohmann::json::parse(vehicle::full_vehicle_preset_json("hmmwv"));
  const nlohmann::json pitman = j["steering"];
  j["steering"] = {{"template", "rack_pinion"},
                   {"name", "test rack"},
                   {"rack", {{"mass", 9.07}, {"com", {0.129, 0, 0}}, {"inertia", {1, 1, 1}}}},
                   {"axis", {0, -1, 0}},
                   {"pinion", {{"radius", 0.1}, {"max_angle", 0.87}}},
                   {"location", pitman["location"]},
                   {"orientation", pitman["orientation"]}};
  return j;
}

inline vehicle::FullVehicleSpec hmmwv_with_rack() {
  return vehicle::read_full_vehicle(hmmwv_rack_json(), "HMMWV with a rack");
}

}  // namespace terracal::test
