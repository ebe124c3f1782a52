#pragma once
// A ParaView snapshot of the full vehicle's bodies as they are now: one .vtu (core/vtu_writer.hpp).
// Each wheel is a closed cylinder (the tire's unloaded radius and drawn width, about the spindle's
// spin axis y, centred on the spindle); the chassis is the box, in its own frame, around the points the
// suspensions, springs and steering attach to it and its centre of mass; every other body (arms,
// uprights, steering link, Pitman arm) is the line segments between each two of the points it carries
// (its joints' points, and its springs' and shocks' ends), in the world. Each distance joint (tie rods,
// the steering's idler) and each spring and shock is one more line between its two ends.
// Cell data: `body`, the body's index in the system (-1 for the joints and springs drawn as lines), and
// `name_id`, the part's index in kVehicleVtuNames. Point data: `velocity`, world, m/s (of the body the
// point is on; a spring's or a joint's ends move with the bodies they join).
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "core/range.hpp"
#include "core/vtu_writer.hpp"
#include "highfi/vehicle/full_vehicle.hpp"

namespace terracal::vehicle {

// The names that the cell array `name_id` indexes.
enum class VtuPart : int {
  chassis,
  wheel,
  upright,
  upper_arm,
  lower_arm,
  steering_link,
  pitman_arm,
  tie_rod,
  idler,
  distance_link,
  spring,
  other_body
};
inline constexpr std::array<const char*, 12> kVehicleVtuNames = {
    "chassis",    "wheel",   "upright", "upper arm",     "lower arm",       "steering link",
    "Pitman arm", "tie rod", "idler",   "distance link", "spring or shock", "other body"};

// Snapshots per second of `terracal vehicle --vtu` (--vtu-rate).
inline constexpr Range kVehicleVtuRate{0, 1000, true, false, "Hz"};

// Facets around a drawn wheel.
inline constexpr int kWheelFacets = 32;

// The wheel's drawn width: the vehicle file's wheel.width, or where it gives none 0.6757 of the
// unloaded radius (the HMMWV's 37x12.5R16.5 tire: 12.5 in wide, 18.5 in radius).
double drawn_tire_width(const FullVehicleSpec& spec);

// The mesh of the vehicle's bodies now (world coordinates).
struct VehicleMesh {
  std::vector<double> xyz;      // x, y, z per point
  std::vector<float> velocity;  // 3 per point, world, m/s
  VtuCells cells;
  std::vector<int> body, name_id;  // per cell
};

VehicleMesh vehicle_mesh(const FullVehicle& v, int wheel_facets = kWheelFacets);

// The names of the system's bodies, by the index that the cell array `body` holds.
std::vector<std::string> vehicle_body_names(const FullVehicle& v);

// Writes vehicle_mesh(v) to `file` (through a temporary name and a rename) with the time `time` (s).
void write_vehicle_vtu(const std::filesystem::path& file, const FullVehicle& v, double time);

}  // namespace terracal::vehicle
