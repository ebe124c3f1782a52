#pragma once
// One row of trajectory.csv, as every model reports it (docs/formats.md, "trajectory.csv").
namespace terracal::rom {

struct RomSample {
  double time = 0, x = 0, y = 0, z = 0, yaw = 0, roll = 0, pitch = 0;
  double vx = 0, vy = 0, yaw_rate = 0, roll_rate = 0, ax = 0, ay = 0;
  double engine_speed_rpm = 0;
  int gear = 0;  // 1-based in the file, as drivers count
};

}  // namespace terracal::rom
