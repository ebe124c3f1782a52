#pragma once
// One row of trajectory.csv, as every model reports it (docs/formats.md, "trajectory.csv").
#include "core/host_device.hpp"
#include "rom/rom_vehicle.hpp"

namespace terracal::rom {

struct RomSample {
  double time = 0, x = 0, y = 0, z = 0, yaw = 0, roll = 0, pitch = 0;
  double vx = 0, vy = 0, yaw_rate = 0, roll_rate = 0, ax = 0, ay = 0;
  double engine_speed_rpm = 0;
  int gear = 0;  // 1-based in the file, as drivers count
};

// The planar part every model has (positions, speeds, yaw rate, accelerations, engine and gear);
// each model adds its own (roll, heave, pitch).
template <class M>
TERRACAL_HD_INLINE RomSample planar_sample(double t, const double* y, const RomAux& aux, int gear) {
  RomSample s;
  s.time = t;
  s.x = y[M::kX];
  s.y = y[M::kY];
  s.yaw = y[M::kYaw];
  s.vx = y[M::kVx];
  s.vy = y[M::kVy];
  s.yaw_rate = y[M::kYawRate];
  s.ax = aux.ax;
  s.ay = aux.ay;
  s.engine_speed_rpm = aux.engine_speed * 30.0 / 3.14159265358979323846;
  s.gear = gear + 1;
  return s;
}

}  // namespace terracal::rom
