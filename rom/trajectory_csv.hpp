#pragma once
// DIR/trajectory.csv (docs/formats.md): time,x,y,z,yaw,roll,pitch,vx,vy,yaw_rate,roll_rate,ax,ay,
// engine_speed_rpm,gear; written to a temporary name and renamed.
#include <string>
#include <vector>

#include "rom/rom_sample.hpp"

namespace terracal::rom {

inline constexpr const char* kTrajectoryHeader =
    "time,x,y,z,yaw,roll,pitch,vx,vy,yaw_rate,roll_rate,ax,ay,engine_speed_rpm,gear";

void write_trajectory_csv(const std::string& path, const std::vector<RomSample>& samples);

}  // namespace terracal::rom
