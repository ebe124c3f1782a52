#pragma once
// Reference folders made by a ROM with known parameters plus seeded noise, for the calibrate-rom and
// validate-rom tests: DIR/<name>/inputs.txt and trajectory.csv (time, vx, yaw_rate, roll, ay at 20 Hz
// from 0 to `end`, started at 6 m/s; the first row exact: it gives the initial speed).
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <catch2/catch.hpp>

#include "core/rng.hpp"
#include "rom/rom_forward.hpp"
#include "rom/rom_vehicle_json.hpp"
#include "tests/apps/cli_runner.hpp"

namespace terracal::test {

inline constexpr double kRomRefNoise[] = {0.03, 0.01, 0.002, 0.1};  // vx, yaw rate, roll, ay

inline void write_rom_reference(const std::string& dir, const std::string& name, const char* inputs,
                                rom::RomModel model, const std::vector<std::string>& params,
                                const std::vector<double>& truth, double end, std::uint64_t seed,
                                std::uint64_t stream) {
  const std::string folder = dir + "/" + name;
  std::filesystem::create_directories(folder);
  write(folder + "/inputs.txt", inputs);
  std::vector<rom::RomReference> refs = {
      rom::RomReference{.dir = folder, .name = name, .driver = DriverSeries::read(folder + "/inputs.txt")}};
  rom::RomReference& r = refs[0];
  r.initial_speed = 6.0;
  for (int i = 0; i <= static_cast<int>(std::lround(end * 20)); ++i) r.time.push_back(0.05 * i);
  const std::vector<rom::RomChannel> ch = {rom::kRcVx, rom::kRcYawRate, rom::kRcRoll, rom::kRcAy};
  for (auto c : ch) r.has[c] = true;
  const rom::RomForward f({rom::load_rom_vehicle("hmmwv"), model, params, ch, &refs, 1e-3, rom::BatchDevice::kCpu});
  std::vector<std::vector<double>> out;
  f({truth}, out);
  REQUIRE(out[0].size() == 4 * r.time.size());
  Rng rng = Rng::for_stream(seed, stream);
  std::string csv = "time,vx,yaw_rate,roll,ay\n";
  for (std::size_t i = 0; i < r.time.size(); ++i) {
    csv += fmt::format("{:.6f}", r.time[i]);
    for (std::size_t c = 0; c < ch.size(); ++c)
      csv += fmt::format(",{:.12g}", out[0][c * r.time.size() + i] + (i == 0 ? 0.0 : kRomRefNoise[c] * rng.normal()));
    csv += "\n";
  }
  write(folder + "/trajectory.csv", csv);
}

}  // namespace terracal::test
