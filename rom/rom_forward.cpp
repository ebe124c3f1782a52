#include "rom/rom_forward.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/errors.hpp"
#include "rom/batch_vary.hpp"
#include "rom/rom_vehicle_json.hpp"

namespace terracal::rom {

namespace {
// Batches of fewer runs than this per CPU thread run on the CPU even where the device is a GPU.
constexpr int kSmallBatchRunsPerThread = 8;

// Where a reference row at `time` lies among a batch's `samples` samples at `rate`: linear between
// s0 and s1 at weight w towards s1.
struct BetweenSamples {
  int s0 = 0, s1 = 0;
  double w = 0;
};
inline BetweenSamples between_samples(double time, double rate, int samples) {
  double s = time * rate;
  if (std::fabs(s - std::round(s)) < 1e-9) s = std::round(s);  // on a sample: that sample, to the bit
  const int s0 = std::clamp(static_cast<int>(std::floor(s)), 0, samples - 1);
  return {s0, std::min(s0 + 1, samples - 1), std::clamp(s - s0, 0.0, 1.0)};
}
}  // namespace

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
    first_row_.push_back(rows_);
    rows_ += r.time.size();
    // The batch runs one sample beyond the last time; each row lies between two samples.
    const double rate = rate_.back();
    const long every = static_cast<long>(1.0 / (rate * s_.step) + 0.5);
    samples_.push_back(static_cast<int>(static_cast<long>((r.end_time() + 1.0 / rate) / s_.step + 0.5) / every) + 1);
    BatchTargets t;
    for (double time : r.time) {
      const BetweenSamples b = between_samples(time, rate, samples_.back());
      t.s0.push_back(b.s0);
      t.s1.push_back(b.s1);
      t.w.push_back(b.w);
    }
    for (RomChannel c : s_.channels) t.y.insert(t.y.end(), r.values[c].begin(), r.values[c].end());
    targets_.push_back(std::move(t));
  }
}

RomVehicle RomForward::vehicle(const std::vector<double>& p) const {
  RomVehicle v = s_.base;
  for (std::size_t j = 0; j < s_.parameters.size(); ++j) apply_vary_parameter(v, s_.base, s_.parameters[j], p[j]);
  return v;
}

// One batch of every vehicle on every reference of `group` (all sampled at one rate): vehicle i on
// reference group[r] is run i + r n, with that reference's driver, initial speed and end time.
void RomForward::run_group(const std::vector<std::size_t>& group, const std::vector<RomVehicle>& vehicles,
                           std::vector<std::vector<double>>& out, std::vector<char>& ok, bool compare) const {
  const long n = static_cast<long>(vehicles.size());
  const long runs = n * static_cast<long>(group.size());
  const double rate = rate_[group[0]];
  BatchOptions o;
  o.model = s_.model;
  o.step = s_.step;
  o.output_rate = rate;
  for (RomChannel c : s_.channels) o.channels.push_back(batch_channel(c));
  // A GPU launch lasts as long as its longest run whatever the batch's size, so small batches (the
  // least-squares stage's, a few runs each) run on the CPU threads: on a 16-core host the point
  // estimate took 27 s through the GPU and 3 s on the CPU.
  o.device = s_.device == BatchDevice::kCuda && s_.small_batches_on_cpu &&
                     runs < kSmallBatchRunsPerThread * omp_get_max_threads()
                 ? BatchDevice::kCpu
                 : s_.device;
  std::vector<RomVehicle>& all = all_;  // kept from call to call, with the batch's result (no new pages)
  all.clear();
  std::vector<const DriverSeries*> drivers;
  for (std::size_t k : group) {
    const RomReference& ref = (*s_.references)[k];
    all.insert(all.end(), vehicles.begin(), vehicles.end());
    drivers.insert(drivers.end(), n, &ref.driver);
    o.initial_speeds.insert(o.initial_speeds.end(), n, ref.initial_speed);
    o.end_times.insert(o.end_times.end(), n, ref.end_time() + 1.0 / rate);  // a sample beyond the last time
    if (compare) o.targets.insert(o.targets.end(), n, &targets_[k]);
  }
  o.end_time = *std::max_element(o.end_times.begin(), o.end_times.end());
  run_rom_batch(all, drivers, runs, o, batch_);
  const BatchResult& b = batch_;
  stats_.runs += runs;
  stats_.wall_seconds += b.wall_seconds;
  stats_.stepping_seconds += b.stepping_seconds;
  for (std::size_t r = 0; r < group.size(); ++r) {
    const BatchTargets& t = targets_[group[r]];  // the reference's rows on the batch's samples
#pragma omp parallel for schedule(static)
    for (long i = 0; i < n; ++i) {
      const long run = static_cast<long>(r) * n + i;
      if (b.metrics[kMetFailedAt * runs + run] >= 0) ok[i] = 0;
      if (!ok[i]) continue;
      for (std::size_t c = 0; c < s_.channels.size(); ++c) {
        if (compare) {
          out[i][c] += b.sse[c * runs + run];
          continue;
        }
        double* dst = out[i].data() + c * rows_ + first_row_[group[r]];
        const auto at = [&](int sample) { return b.channels[(c * b.samples + sample) * runs + run]; };
        for (std::size_t row = 0; row < t.w.size(); ++row)
          dst[row] = (1 - t.w[row]) * at(t.s0[row]) + t.w[row] * at(t.s1[row]);
      }
    }
  }
}

std::vector<RomVehicle> RomForward::vehicles_of(const std::vector<std::vector<double>>& params,
                                                std::vector<char>& ok) const {
  ok.assign(params.size(), 1);
  std::vector<RomVehicle> vehicles(params.size());
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < params.size(); ++i) {
    vehicles[i] = vehicle(params[i]);
    try {
      validate(vehicles[i], "calibration");
    } catch (const InputError&) {
      ok[i] = 0;
      vehicles[i] = s_.base;  // runs, but its result is dropped
    }
  }
  return vehicles;
}

// References sampled at one rate run as one batch: each parameter set once per reference.
std::vector<std::vector<std::size_t>> RomForward::groups() const {
  std::vector<std::vector<std::size_t>> out;
  std::vector<char> done(s_.references->size(), 0);
  for (std::size_t k0 = 0; k0 < s_.references->size(); ++k0) {
    if (done[k0]) continue;
    out.emplace_back();
    for (std::size_t k = k0; k < s_.references->size(); ++k)
      if (!done[k] && rate_[k] == rate_[k0]) {
        out.back().push_back(k);
        done[k] = 1;
      }
  }
  return out;
}

void RomForward::operator()(const std::vector<std::vector<double>>& params,
                            std::vector<std::vector<double>>& out) const {
  const auto start = std::chrono::steady_clock::now();
  out.assign(params.size(), std::vector<double>(s_.channels.size() * rows_));
  std::vector<char> ok;
  const std::vector<RomVehicle> vehicles = vehicles_of(params, ok);
  for (const auto& group : groups()) run_group(group, vehicles, out, ok, false);
  for (std::size_t i = 0; i < params.size(); ++i)
    if (!ok[i]) out[i].clear();
  stats_.call_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void RomForward::sse(const std::vector<std::vector<double>>& params, std::vector<std::vector<double>>& out) const {
  const auto start = std::chrono::steady_clock::now();
  out.assign(params.size(), std::vector<double>(s_.channels.size(), 0.0));
  std::vector<char> ok;
  const std::vector<RomVehicle> vehicles = vehicles_of(params, ok);
  for (const auto& group : groups()) run_group(group, vehicles, out, ok, true);
  for (std::size_t i = 0; i < params.size(); ++i)
    if (!ok[i]) out[i].clear();
  stats_.call_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace terracal::rom
