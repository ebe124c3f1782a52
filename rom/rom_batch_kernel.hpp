#pragma once
// The body of the batch loop: vehicle i steps from rest (or its initial speed) to the end time with
// the half-implicit scheme, keeping its state in registers, and writes its summary metrics, its
// final state and its sampled channels once. Compiled for the CPU (OpenMP, one iteration per vehicle)
// and the GPU (`Lanes` threads per vehicle, one per wheel of the four-wheel models: rom/wheel_group.hpp)
// from this one source.
#include <algorithm>
#include <cmath>
#include <vector>

#include "core/host_device.hpp"
#include "core/vehicle/driver_inputs.hpp"
#include "rom/half_implicit.hpp"
#include "rom/rom_batch.hpp"
#include "rom/wheel_group.hpp"

namespace terracal::rom {

// BatchTargets as a kernel reads them (host or device pointers).
struct BatchTargetView {
  const int* s0 = nullptr;
  const int* s1 = nullptr;
  const double* w = nullptr;
  const double* y = nullptr;
  long rows = 0;
};

// A run's comparison with its targets so far: the previous sample's values, the sums, the next row.
struct BatchComparison {
  double prev[kBatchChannelCount] = {};
  double sum[kBatchChannelCount] = {};
  long row = 0;
};

template <class M, int Lanes = 1>
struct BatchKernel {
  using Group = WheelGroup<Lanes>;
  const RomVehicle* vehicles = nullptr;  // n_vehicles entries (1: shared)
  long n_vehicles = 1;
  const DriverSeriesView* drivers = nullptr;  // n_drivers entries (1: shared)
  long n_drivers = 1;
  long first = 0;  // index of this chunk's first vehicle in the whole batch
  long count = 0;  // vehicles in this chunk
  double step = 1e-3;
  long steps = 0;
  double initial_speed = 0;
  // Per driver (n_drivers entries), or null: initial_speed and steps for every vehicle.
  const double* initial_speeds = nullptr;
  const long* driver_steps = nullptr;
  long sample_every = 0;  // steps between channel samples; 0: none
  int samples = 0;
  int n_channels = 0;
  int channel[kBatchChannelCount] = {};
  bool sample_aux = false;        // a channel (ax, ay) needs the right-hand side at the sample
  double* metrics = nullptr;      // [metric][count]
  double* channels = nullptr;     // [channel][sample][count]
  double* final_state = nullptr;  // [state][count]
  // With targets (n_drivers entries): each run's sums of squared differences go to sse
  // ([channel][count]) and no sample to channels.
  const BatchTargetView* targets = nullptr;
  double* sse = nullptr;

  TERRACAL_HD static double channel_value(int c, const double* y, const RomAux& aux) {
    switch (c) {
      case kChX:
        return y[M::kX];
      case kChY:
        return y[M::kY];
      case kChYaw:
        return y[M::kYaw];
      case kChVx:
        return y[M::kVx];
      case kChVy:
        return y[M::kVy];
      case kChYawRate:
        return y[M::kYawRate];
      case kChAx:
        return aux.ax;
      case kChAy:
        return aux.ay;
      default:
        return M::roll_of(y);
    }
  }

  // Sample s at state y with the right-hand side's aux there (ax, ay): the next step's, whose inputs are
  // those at the sample's time, as a single run samples them (rom_run.cpp). With targets, the sample is
  // compared instead (`cmp`, `t`).
  TERRACAL_HD void record(int s, long i, const double* y, const RomAux& aux, const Group& lanes, BatchComparison& cmp,
                          const BatchTargetView* t) const {
    if (t) {
      compare(s, y, aux, *t, cmp);
      return;
    }
    if (!lanes.leader()) return;
    for (int c = 0; c < n_channels; ++c)
      channels[(long(c) * samples + s) * count + i] = channel_value(channel[c], y, aux);
  }

  // The rows whose later sample is s, interpolated as the calibrator's forward model does on the
  // host (rom_forward.cpp), their squared differences added in row order.
  TERRACAL_HD void compare(int s, const double* y, const RomAux& aux, const BatchTargetView& t,
                           BatchComparison& cmp) const {
    double value[kBatchChannelCount];
    for (int c = 0; c < n_channels; ++c) value[c] = channel_value(channel[c], y, aux);
    for (; cmp.row < t.rows && t.s1[cmp.row] == s; ++cmp.row) {
      const long r = cmp.row;
      const double w = t.w[r];
      const bool same = t.s0[r] == s;
      for (int c = 0; c < n_channels; ++c) {
        const double d = t.y[c * t.rows + r] - ((1 - w) * (same ? value[c] : cmp.prev[c]) + w * value[c]);
        cmp.sum[c] += d * d;
      }
    }
    for (int c = 0; c < n_channels; ++c) cmp.prev[c] = value[c];
  }

  // Iteration t: vehicle t / Lanes of this chunk, wheel t % Lanes (the GPU's threads; the CPU's
  // iterations with one lane).
  TERRACAL_HD void operator()(long t) const {
#if defined(__CUDA_ARCH__)
    const Group lanes = wheel_group_of<Lanes>(t);
#else
    const Group lanes;  // one lane: groups share a vehicle through warp shuffles, on the GPU only
#endif
    const long i = t / Lanes, g = first + i;
    if (n_vehicles == 1 || Lanes > 1) {
      // Shared: every thread reads the same (cached) parameters; or a group's lanes read their one
      // vehicle's fields together.
      simulate(vehicles[n_vehicles == 1 ? 0 : g], i, g, lanes);
    } else {
      // Own parameters: a private copy, which the GPU lays out thread-interleaved (its local
      // memory), so neighbouring threads' reads of one field coalesce instead of striding by
      // sizeof(RomVehicle).
      const RomVehicle own = vehicles[g];
      simulate(own, i, g, lanes);
    }
  }

  // Every lane of a group steps the same state (the same bits); the leader writes the outputs.
  TERRACAL_HD void simulate(const RomVehicle& v, long i, long g, const Group& lanes) const {
    const long di = n_drivers == 1 ? 0 : g;
    const DriverSeriesView& d = drivers[di];
    const long steps = driver_steps ? driver_steps[di] : this->steps;
    double y[M::kStates];
    int gear = M::initial_state(v, initial_speeds ? initial_speeds[di] : initial_speed, y);
    RomAux aux;
    double max_ay = 0, max_r = 0, max_roll = 0, failed_at = -1;
    BatchComparison cmp;
    const BatchTargetView* t = targets ? &targets[di] : nullptr;
    // A sample is taken at the start of the next step, from that step's right-hand side (no
    // right-hand side of its own: one in sample_every fewer); the last one after the loop.
    int pending = sample_every > 0 ? 0 : -1;
    const auto take_pending = [&](const double* ys, const RomAux& a) {
      if (pending < 0) return;
      record(pending, i, ys, a, lanes, cmp, t);
      pending = -1;
    };
    int cursor = 0;  // the driver's row at the last step
    for (long k = 0; k < steps; ++k) {
      const DriverInput in = d.at(k * step, cursor);
      if (!half_implicit_step<M>(v, in, gear, y, step, &aux, lanes, take_pending)) {
        failed_at = (k + 1) * step;
        break;
      }
      max_ay = max_of(max_ay, fabs(aux.ay));
      max_r = max_of(max_r, fabs(y[M::kYawRate]));
      max_roll = max_of(max_roll, fabs(M::roll_of(y)));
      if (sample_every > 0 && (k + 1) % sample_every == 0) pending = int((k + 1) / sample_every);
    }
    if (pending >= 0) {
      RomAux end;
      if (sample_aux) {
        double dy[M::kStates];
        M::rhs(v, d.at(steps * step, cursor), gear, y, dy, &end, true, true, lanes);
      }
      take_pending(y, end);
    }
    if (!lanes.leader()) return;
    const double m[kBatchMetricCount] = {y[M::kX], y[M::kY], y[M::kYaw], y[M::kVx], max_ay, max_r, max_roll, failed_at};
    for (int k = 0; k < kBatchMetricCount; ++k) metrics[long(k) * count + i] = m[k];
    for (int k = 0; k < M::kStates; ++k) final_state[long(k) * count + i] = y[k];
    if (t)
      for (int c = 0; c < n_channels; ++c) sse[long(c) * count + i] = cmp.sum[c];
  }
};

// The steps of each driver's runs (BatchOptions::end_times), or of every run: one entry.
inline std::vector<long> batch_steps(const BatchOptions& o) {
  std::vector<long> out;
  for (double t : o.end_times.empty() ? std::vector<double>{o.end_time} : o.end_times)
    out.push_back(static_cast<long>(t / o.step + 0.5));
  return out;
}

// The loop's settings from the options, and the result's arrays sized for n vehicles (host code;
// the CPU and GPU batches share it).
template <class M, int Lanes = 1>
BatchKernel<M, Lanes> configure_batch(const BatchOptions& o, long n_vehicles, long n_drivers, long n, BatchResult& r) {
  BatchKernel<M, Lanes> k;
  k.n_vehicles = n_vehicles;
  k.n_drivers = n_drivers;
  k.step = o.step;
  k.steps = 0;
  for (long s : batch_steps(o)) k.steps = std::max(k.steps, s);
  k.initial_speed = o.initial_speed;
  k.sample_every = o.output_rate > 0 ? static_cast<long>(1.0 / (o.output_rate * o.step) + 0.5) : 0;
  k.samples = k.sample_every > 0 ? static_cast<int>(k.steps / k.sample_every) + 1 : 0;
  k.n_channels = k.sample_every > 0 ? static_cast<int>(o.channels.size()) : 0;
  for (int c = 0; c < k.n_channels; ++c) {
    k.channel[c] = o.channels[c];
    k.sample_aux = k.sample_aux || o.channels[c] == kChAx || o.channels[c] == kChAy;
  }
  r.vehicles = n;
  r.samples = k.samples;
  r.states = M::kStates;
  r.metrics.assign(static_cast<std::size_t>(kBatchMetricCount) * n, 0.0);
  // With targets, sums in place of samples.
  const bool compared = !o.targets.empty();
  r.channels.assign(compared ? 0 : static_cast<std::size_t>(k.n_channels) * k.samples * n, 0.0);
  r.sse.assign(compared ? static_cast<std::size_t>(k.n_channels) * n : 0, 0.0);
  r.final_state.assign(static_cast<std::size_t>(M::kStates) * n, 0.0);
  return k;
}

// Vehicles whose state diverged (a failure time was recorded).
inline long count_failed(const BatchResult& r) {
  long failed = 0;
  for (long i = 0; i < r.vehicles; ++i)
    failed += r.metrics[static_cast<std::size_t>(kMetFailedAt) * r.vehicles + i] >= 0;
  return failed;
}

}  // namespace terracal::rom
