#pragma once
// A reference manoeuvre for calibrating or validating a reduced-order vehicle: a run's folder
// holding trajectory.csv (at least `time`, `vx` and the channels compared) and the driver file
// inputs.txt that drove it (docs/formats.md, "ROM references"). `terracal vehicle` and
// `terracal rom` write both.
#include <array>
#include <string>
#include <vector>

#include "core/vehicle/driver_inputs.hpp"

namespace terracal::rom {

// The channels a ROM is compared on, in the order the calibrator lists them.
enum RomChannel : int { kRcVx, kRcYawRate, kRcRoll, kRcAy, kRomChannelCount };
inline constexpr const char* kRomChannelNames[] = {"vx", "yaw_rate", "roll", "ay"};
inline constexpr const char* kRomChannelUnits[] = {"m/s", "rad/s", "rad", "m/s^2"};

struct RomReference {
  std::string dir;   // the folder, as given
  std::string name;  // its last path component, for labels
  DriverSeries driver;
  double initial_speed = 0;  // vx of the first row [m/s]
  std::vector<double> time{};  // sample times, from 0, strictly increasing [s]
  std::array<std::vector<double>, kRomChannelCount> values{};
  std::array<bool, kRomChannelCount> has{};  // the file has that column
  double end_time() const { return time.back(); }
};

// Reads DIR/trajectory.csv and DIR/inputs.txt. Throws InputError naming the file, line and column for
// a missing file or column, a time that does not start at 0 or does not increase, fewer than 3 rows,
// or a sample spacing below 1 ms.
RomReference read_rom_reference(const std::string& dir);

// "a,b,c" -> the folders; an empty item is an InputError naming `option`.
std::vector<std::string> split_dirs(const std::string& list, const std::string& option);

}  // namespace terracal::rom
