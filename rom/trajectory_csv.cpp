#include "rom/trajectory_csv.hpp"

#include <fmt/format.h>

#include "core/atomic_file.hpp"

namespace terracal::rom {

void write_trajectory_csv(const std::string& path, const std::vector<RomSample>& samples) {
  std::string s = std::string(kTrajectoryHeader) + "\n";
  s.reserve(samples.size() * 200);
  for (const RomSample& r : samples)
    s += fmt::format(
        "{:.6g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.6g},{}\n",
        r.time, r.x, r.y, r.z, r.yaw, r.roll, r.pitch, r.vx, r.vy, r.yaw_rate, r.roll_rate, r.ax, r.ay,
        r.engine_speed_rpm, r.gear);
  write_text_atomically(path, s);
}

}  // namespace terracal::rom
