#include "rom/rom_forward.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/errors.hpp"
#include "rom/batch_vary.hpp"
#include "rom/rom_vehicle_json.hpp"

namespace terracal::rom {

BatchChannel batch_channel(RomChannel c) {
  switch (c) {
    case kRcVx:
      return kChVx;
    case kRcYawRate:
      return kChYawRate;
    case kRcRoll:
      return kChRoll;
    case kRcAy:
      return kChAy;
    default:
      return kChVx;
  }
}

RomForward::RomForward(RomForwardSetup setup) : s_(std::move(setup)) {
  const auto& names = vary_parameter_names();
  for (const auto& p : s_.parameters)
    if (std::find(names.begin(), names.end(), p) == names.end())
      throw InputError(
          fmt::format("parameter '{}': not a vehicle parameter; expected one of {}", p, fmt::join(names, ", ")));
  if (!s_.references || s_.references->empty()) throw InputError("calibration: no reference manoeuvre");
  for (const RomReference& r : *s_.references) {
    for (RomChannel c : s_.channels)
      if (!r.has[c])
        throw InputError(fmt::format("{}/trajectory.csv: no column '{}' to compare", r.dir, kRomChannelNames[c]));
    // Samples on the batch's output grid: the reference's smallest spacing, a whole number of steps.
    double dt = std::numeric_limits<double>::infinity();
    for (std::size_t i = 1; i < r.time.size(); ++i) dt = std::min(dt, r.time[i] - r.time[i - 1]);
    const double steps = std::max(1.0, std::round(dt / s_.step));
    rate_.push_back(1.0 / (steps * s_.step));
    rows_ += r.time.size();
  }
}

RomVehicle RomForward::vehicle(const std::vector<double>& p) const {
  RomVehicle v = s_.base;
  for (std::size_t j = 0; j < s_.parameters.size(); ++j) apply_vary_parameter(v, s_.base, s_.parameters[j], p[j]);
  return v;
}

void RomForward::operator()(const std::vector<std::vector<double>>& params,
                            std::vector<std::vector<double>>& out) const {
  const long n = static_cast<long>(params.size());
  out.assign(params.size(), std::vector<double>(s_.channels.size() * rows_));
  std::vector<char> ok(params.size(), 1);
  std::vector<RomVehicle> vehicles;
  for (const auto& p : params) {
    vehicles.push_back(vehicle(p));
    try {
      validate(vehicles.back(), "calibration");
    } catch (const InputError&) {
      ok[vehicles.size() - 1] = 0;
      vehicles.back() = s_.base;  // runs, but its result is dropped
    }
  }
  std::size_t first_row = 0;
  for (std::size_t k = 0; k < s_.references->size(); ++k) {
    const RomReference& ref = (*s_.references)[k];
    BatchOptions o;
    o.model = s_.model;
    o.step = s_.step;
    o.end_time = ref.end_time() + 1.0 / rate_[k];  // a sample beyond the last reference time
    o.initial_speed = ref.initial_speed;
    o.output_rate = rate_[k];
    for (RomChannel c : s_.channels) o.channels.push_back(batch_channel(c));
    o.device = s_.device;
    const BatchResult b = run_rom_batch(vehicles, {&ref.driver}, n, o);
    stats_.runs += n;
    stats_.wall_seconds += b.wall_seconds;
    for (long i = 0; i < n; ++i) {
      if (b.metrics[kMetFailedAt * n + i] >= 0) ok[i] = 0;
      if (!ok[i]) continue;
      for (std::size_t c = 0; c < s_.channels.size(); ++c) {
        double* dst = out[i].data() + c * rows_ + first_row;
        for (std::size_t r = 0; r < ref.time.size(); ++r) {
          // Linear between the batch's samples s = time * rate.
          double s = ref.time[r] * rate_[k];
          if (std::fabs(s - std::round(s)) < 1e-9) s = std::round(s);  // on a sample: that sample, to the bit
          const int s0 = std::clamp(static_cast<int>(std::floor(s)), 0, b.samples - 1);
          const int s1 = std::min(s0 + 1, b.samples - 1);
          const double w = std::clamp(s - s0, 0.0, 1.0);
          const auto at = [&](int sample) { return b.channels[(c * b.samples + sample) * n + i]; };
          dst[r] = (1 - w) * at(s0) + w * at(s1);
        }
      }
    }
    first_row += ref.time.size();
  }
  for (std::size_t i = 0; i < params.size(); ++i)
    if (!ok[i]) out[i].clear();
}

}  // namespace terracal::rom
