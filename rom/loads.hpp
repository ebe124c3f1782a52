#pragma once
// Quasi-static vertical tire loads of the models without suspension travel (11 and 18 DOF): the
// static axle loads, longitudinal transfer through the CG heights, and (18 DOF) lateral transfer per
// axle through the roll centre and the roll spring and damper. Wheels cannot lift off: a load below
// zero is clamped to zero by the tire.
#include "core/host_device.hpp"
#include "rom/rom_vehicle.hpp"

namespace terracal::rom {

// Front and rear axle loads under a longitudinal acceleration ax [N]. a and b locate the whole
// vehicle's CG, where the models apply its mass; the unsprung masses count in the transfer heights.
struct AxleLoads {
  double front = 0, rear = 0;
};
TERRACAL_HD_INLINE AxleLoads axle_loads(const RomVehicle& v, double ax) {
  const double l = v.wheelbase(), g = v.gravity;
  const double unsprung_height = 0.5 * (v.tire[0].unloaded_radius + v.tire[1].unloaded_radius);
  const double transfer = ax * (v.mass * v.cg_height + (v.unsprung_mass[0] + v.unsprung_mass[1]) * unsprung_height) / l;
  AxleLoads f;
  f.front = v.total_mass() * g * v.cg_to_rear / l - transfer;
  f.rear = v.total_mass() * g * v.cg_to_front / l + transfer;
  return f;
}

// Height of the roll axis under the sprung CG, and the CG's height above it.
TERRACAL_HD_INLINE double roll_arm(const RomVehicle& v) {
  const double hrc = (v.roll_center_height[0] * v.cg_to_rear + v.roll_center_height[1] * v.cg_to_front) / v.wheelbase();
  return v.cg_height - hrc;
}

// The steady roll angle under ay (the `roll` effect off): K phi = m ay hs + m g hs phi.
TERRACAL_HD_INLINE double steady_roll(const RomVehicle& v, double ay) {
  const double hs = roll_arm(v);
  return v.mass * ay * hs / (v.roll_stiffness[0] + v.roll_stiffness[1] - v.mass * v.gravity * hs);
}

// Load moved from the left to the right wheel of axle i (0 front, 1 rear) [N].
TERRACAL_HD_INLINE double lateral_transfer(const RomVehicle& v, int i, double ay, double roll, double roll_rate) {
  const double share = i == 0 ? v.cg_to_rear / v.wheelbase() : v.cg_to_front / v.wheelbase();
  const double moment = v.mass * share * ay * v.roll_center_height[i] + v.roll_stiffness[i] * roll +
                        v.roll_damping[i] * roll_rate + v.unsprung_mass[i] * ay * v.tire[i].unloaded_radius;
  return moment / v.track[i];
}

}  // namespace terracal::rom
