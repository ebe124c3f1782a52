#include "rom/rom_reference.hpp"

#include <filesystem>

#include <fmt/format.h>

#include "core/csv.hpp"
#include "core/errors.hpp"

namespace terracal::rom {

RomReference read_rom_reference(const std::string& dir) {
  namespace fs = std::filesystem;
  const std::string traj = (fs::path(dir) / "trajectory.csv").string();
  const std::string inputs = (fs::path(dir) / "inputs.txt").string();
  if (!fs::is_directory(dir)) throw InputError(fmt::format("reference {}: not a folder", dir));
  if (!fs::exists(traj)) throw InputError(fmt::format("reference {}: no trajectory.csv in it", dir));
  if (!fs::exists(inputs))
    throw InputError(
        fmt::format("reference {}: no inputs.txt (the driver file of the run) beside trajectory.csv", dir));
  std::string name = fs::path(dir).lexically_normal().filename().string();
  if (name.empty() || name == ".") name = fs::path(dir).lexically_normal().parent_path().filename().string();
  RomReference r{.dir = dir, .name = name, .driver = DriverSeries::read(inputs)};
  const CsvTable t = CsvTable::read(traj);
  t.require_columns({"time", "vx"});
  if (t.rows() < 3) throw InputError(fmt::format("{}: {} rows; expected at least 3", traj, t.rows()));
  for (int c = 0; c < kRomChannelCount; ++c) r.has[c] = t.has_column(kRomChannelNames[c]);
  for (std::size_t i = 0; i < t.rows(); ++i) {
    const double time = t.number(i, "time");
    if (i == 0 && std::abs(time) > 1e-9)
      throw InputError(fmt::format("{}: time {}: expected the first row at time 0", t.where(i, "time"), time));
    if (i > 0 && !(time - r.time.back() >= 1e-3))
      throw InputError(fmt::format("{}: time {}: expected at least 1 ms after the row before ({})", t.where(i, "time"),
                                   time, r.time.back()));
    r.time.push_back(i == 0 ? 0.0 : time);
    for (int c = 0; c < kRomChannelCount; ++c)
      if (r.has[c]) r.values[c].push_back(t.number(i, kRomChannelNames[c]));
  }
  r.initial_speed = r.values[kRcVx].front();
  return r;
}

std::vector<std::string> split_dirs(const std::string& list, const std::string& option) {
  std::vector<std::string> out;
  std::size_t from = 0;
  for (;;) {
    const std::size_t to = list.find(',', from);
    const std::string item = list.substr(from, to == std::string::npos ? std::string::npos : to - from);
    if (item.empty()) throw InputError(fmt::format("{} '{}': an empty folder name in the list", option, list));
    out.push_back(item);
    if (to == std::string::npos) break;
    from = to + 1;
  }
  return out;
}

}  // namespace terracal::rom
