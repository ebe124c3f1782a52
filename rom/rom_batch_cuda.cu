// The GPU batch: vehicles' parameters and drivers copied once, then chunks of vehicles run as one
// CUDA thread each, or four for the four-wheel models (the same BatchKernel as the CPU), and only the
// reduced outputs come back.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>

#include <fmt/format.h>

#include "core/cuda_check.hpp"
#include "core/errors.hpp"
#include "core/parallel_for_cuda.cuh"
#include "rom/rom_batch_device.hpp"
#include "rom/rom_batch_kernel.hpp"
#include "rom/rom_models.hpp"

namespace terracal::rom {

namespace {

// Device copies that free themselves.
template <class T>
struct DeviceArray {
  T* p = nullptr;
  explicit DeviceArray(std::size_t n) {
    if (n > 0) TERRACAL_CUDA_CHECK(cudaMalloc(&p, n * sizeof(T)));
  }
  DeviceArray(const T* host, std::size_t n) : DeviceArray(n) {
    if (n > 0) TERRACAL_CUDA_CHECK(cudaMemcpy(p, host, n * sizeof(T), cudaMemcpyHostToDevice));
  }
  ~DeviceArray() { cudaFree(p); }
  DeviceArray(const DeviceArray&) = delete;
  DeviceArray& operator=(const DeviceArray&) = delete;
};

// Device memory kept from batch to batch and grown on demand, one per use and host thread: the
// calibrator runs thousands of batches of one size, and a cudaMalloc/cudaFree pair of a few hundred
// MB per launch costs milliseconds (a free waits for the device).
struct DeviceScratch {
  void* p = nullptr;
  std::size_t bytes = 0;
  ~DeviceScratch() { cudaFree(p); }
  template <class T>
  T* ensure(std::size_t n) {
    if (n * sizeof(T) > bytes) {
      if (p) TERRACAL_CUDA_CHECK(cudaFree(p));
      p = nullptr;
      bytes = 0;
      TERRACAL_CUDA_CHECK(cudaMalloc(&p, n * sizeof(T)));
      bytes = n * sizeof(T);
    }
    return static_cast<T*>(p);
  }
};
enum ScratchUse { kVehiclesScratch, kOutputScratch, kScratchUses };
DeviceScratch& device_scratch(ScratchUse use) {
  thread_local DeviceScratch s[kScratchUses];
  return s[use];
}

// The vehicles as the device sees them: a deformable_terrain table's arrays copied into one device
// allocation per distinct table (owned by `tables`), the copies' views pointing into it.
std::vector<RomVehicle> with_device_tables(const std::vector<RomVehicle>& vehicles,
                                           std::vector<std::unique_ptr<DeviceArray<double>>>& tables) {
  std::vector<RomVehicle> out = vehicles;
  std::map<const double*, TerrainTableView> copied;  // keyed by the host table's load axis
  for (RomVehicle& v : out) {
    if (!v.terrain.present()) continue;
    auto [it, fresh] = copied.try_emplace(v.terrain.load);
    if (fresh) {
      const TerrainTableView& h = v.terrain;
      const std::size_t cells = std::size_t(h.n_load) * h.n_slip * h.n_angle;
      std::vector<double> flat;
      auto put = [&](const double* p, std::size_t n) {
        const std::size_t at = flat.size();
        flat.insert(flat.end(), p, p + n);
        return at;
      };
      const std::size_t offsets[6] = {put(h.load, h.n_load),      put(h.slip, h.n_slip),
                                      put(h.angle, h.n_angle),    put(h.thrust, cells),
                                      put(h.resistance, cells),   put(h.lateral, cells)};
      tables.push_back(std::make_unique<DeviceArray<double>>(flat.data(), flat.size()));
      const double* base = tables.back()->p;
      TerrainTableView d = h;
      d.load = base + offsets[0];
      d.slip = base + offsets[1];
      d.angle = base + offsets[2];
      d.thrust = base + offsets[3];
      d.resistance = base + offsets[4];
      d.lateral = base + offsets[5];
      it->second = d;
    }
    v.terrain = it->second;
  }
  return out;
}

template <class M, int Lanes>
void run_device(const std::vector<RomVehicle>& vehicles, const std::vector<const DriverSeries*>& drivers, long n,
                const BatchOptions& o, BatchResult& r) {
  // deformable_terrain tables: each distinct one copied once, the vehicles' views pointed at it.
  std::vector<std::unique_ptr<DeviceArray<double>>> tables;
  std::vector<RomVehicle> with_tables;  // a copy only where some vehicle has a table
  if (std::any_of(vehicles.begin(), vehicles.end(), [](const RomVehicle& v) { return v.terrain.present(); }))
    with_tables = with_device_tables(vehicles, tables);
  const std::vector<RomVehicle>& on_device = with_tables.empty() ? vehicles : with_tables;
  RomVehicle* d_vehicles = device_scratch(kVehiclesScratch).ensure<RomVehicle>(on_device.size());
  TERRACAL_CUDA_CHECK(
      cudaMemcpy(d_vehicles, on_device.data(), on_device.size() * sizeof(RomVehicle), cudaMemcpyHostToDevice));
  // Each driver's four columns on the device, and the views that point at them.
  std::vector<std::unique_ptr<DeviceArray<double>>> columns;
  std::vector<DriverSeriesView> views;
  // Vehicles often share a few series: each distinct one is copied once.
  std::map<const DriverSeries*, DriverSeriesView> copied;
  for (const DriverSeries* d : drivers) {
    auto [it, fresh] = copied.try_emplace(d);
    if (fresh) {
      DriverSeriesView& v = it->second;
      v.n = d->size();
      const std::vector<double>* cols[4] = {&d->times(), &d->steering(), &d->throttle(), &d->braking()};
      const double** slots[4] = {&v.time, &v.steering, &v.throttle, &v.braking};
      for (int c = 0; c < 4; ++c) {
        columns.push_back(std::make_unique<DeviceArray<double>>(cols[c]->data(), cols[c]->size()));
        *slots[c] = columns.back()->p;
      }
    }
    views.push_back(it->second);
  }
  DeviceArray<DriverSeriesView> d_views(views.data(), views.size());
  // Targets alike: each distinct set copied once.
  std::vector<std::unique_ptr<DeviceArray<int>>> target_rows;
  std::vector<std::unique_ptr<DeviceArray<double>>> target_values;
  std::vector<BatchTargetView> target_views;
  std::map<const BatchTargets*, BatchTargetView> copied_targets;
  for (const BatchTargets* t : o.targets) {
    auto [it, fresh] = copied_targets.try_emplace(t);
    if (fresh) {
      target_rows.push_back(std::make_unique<DeviceArray<int>>(t->s0.data(), t->s0.size()));
      target_rows.push_back(std::make_unique<DeviceArray<int>>(t->s1.data(), t->s1.size()));
      target_values.push_back(std::make_unique<DeviceArray<double>>(t->w.data(), t->w.size()));
      target_values.push_back(std::make_unique<DeviceArray<double>>(t->y.data(), t->y.size()));
      it->second = {target_rows[target_rows.size() - 2]->p, target_rows.back()->p,
                    target_values[target_values.size() - 2]->p, target_values.back()->p, t->rows()};
    }
    target_views.push_back(it->second);
  }
  DeviceArray<BatchTargetView> d_targets(target_views.data(), target_views.size());

  BatchKernel<M, Lanes> k =
      configure_batch<M, Lanes>(o, static_cast<long>(vehicles.size()), static_cast<long>(views.size()), n, r);
  k.vehicles = d_vehicles;
  k.drivers = d_views.p;
  k.targets = d_targets.p;  // null without targets
  const bool compared = !o.targets.empty();
  const std::vector<long> steps = batch_steps(o);
  DeviceArray<long> d_steps(steps.data(), o.end_times.empty() ? 0 : steps.size());
  DeviceArray<double> d_speeds(o.initial_speeds.data(), o.initial_speeds.size());
  k.driver_steps = d_steps.p;  // null where empty: the shared values
  k.initial_speeds = d_speeds.p;

  // Outputs per vehicle; the chunk is what fits in 80 % of the free memory (or max_chunk).
  const std::size_t per_channel = compared ? 1 : static_cast<std::size_t>(k.samples);  // a sum, or the samples
  const std::size_t out_doubles = kBatchMetricCount + static_cast<std::size_t>(k.n_channels) * per_channel + M::kStates;
  std::size_t free_bytes = 0, total_bytes = 0;
  TERRACAL_CUDA_CHECK(cudaMemGetInfo(&free_bytes, &total_bytes));
  free_bytes += device_scratch(kOutputScratch).bytes;  // the previous batch's outputs, reused
  long chunk = std::max<long>(1, static_cast<long>(0.8 * free_bytes / (out_doubles * sizeof(double))));
  if (o.max_chunk > 0) chunk = std::min(chunk, o.max_chunk);
  chunk = std::min(chunk, n);
  // Per vehicle: its outputs, its own parameter set and driver view where it has them (the drivers'
  // columns are shared by the vehicles that use them).
  r.bytes_per_vehicle = out_doubles * sizeof(double) + (vehicles.size() > 1 ? sizeof(RomVehicle) : 0) +
                        (drivers.size() > 1 ? sizeof(DriverSeriesView) : 0);
  double* d_out = device_scratch(kOutputScratch).ensure<double>(out_doubles * chunk);
  for (long first = 0; first < n; first += chunk) {
    const long count = std::min(chunk, n - first);
    k.first = first;
    k.count = count;
    k.metrics = d_out;
    double* per_run = d_out + kBatchMetricCount * count;  // the samples, or the sums
    k.channels = compared ? nullptr : per_run;
    k.sse = compared ? per_run : nullptr;
    k.final_state = per_run + static_cast<std::size_t>(k.n_channels) * per_channel * count;
    // Samples past a run's own end (a shorter manoeuvre in a launch with a longer one) read 0.
    if (!compared)
      TERRACAL_CUDA_CHECK(
          cudaMemset(k.channels, 0, static_cast<std::size_t>(k.n_channels) * k.samples * count * sizeof(double)));
    const auto launched = std::chrono::steady_clock::now();
    parallel_for_cuda_spread(count * Lanes, k);
    TERRACAL_CUDA_CHECK(cudaDeviceSynchronize());
    r.stepping_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - launched).count();
    // [quantity][count] blocks of this chunk into [quantity][n] of the whole batch.
    auto fetch = [&](const double* from, std::vector<double>& to, std::size_t rows) {
      TERRACAL_CUDA_CHECK(cudaMemcpy2D(to.data() + first, n * sizeof(double), from, count * sizeof(double),
                                       count * sizeof(double), rows, cudaMemcpyDeviceToHost));
    };
    fetch(k.metrics, r.metrics, kBatchMetricCount);
    if (k.n_channels > 0 && !compared)
      fetch(k.channels, r.channels, static_cast<std::size_t>(k.n_channels) * k.samples);
    if (compared) fetch(k.sse, r.sse, static_cast<std::size_t>(k.n_channels));
    fetch(k.final_state, r.final_state, M::kStates);
    ++r.chunks;
  }
}

}  // namespace

void run_rom_batch_cuda(const std::vector<RomVehicle>& vehicles, const std::vector<const DriverSeries*>& drivers, long n,
                        const BatchOptions& o, BatchResult& r) {
  int count = 0;
  if (cudaGetDeviceCount(&count) != cudaSuccess || count == 0)
    throw RunError("rom batch: --device cuda, but no CUDA device is present");
  static const std::string name = [] {  // a properties query costs milliseconds: once
    cudaDeviceProp prop{};
    TERRACAL_CUDA_CHECK(cudaGetDeviceProperties(&prop, 0));
    return fmt::format("cuda: {}", prop.name);
  }();
  r.device = name;
  const auto start = std::chrono::steady_clock::now();
  with_model(o.model, [&](auto model) {
    using M = decltype(model);
    // A batch that fits on the GPU at once with one lane per wheel (a calibrator's step) lasts one
    // vehicle's time, which the four lanes shorten; a larger one is bound by throughput, which the
    // lanes' repeated chassis arithmetic lowers (rom/wheel_group.hpp).
    if constexpr (M::kWheels == 4) {
      const long per_chunk = o.max_chunk > 0 ? std::min(n, o.max_chunk) : n;
      if (spread_fits_one_wave<BatchKernel<M, 4>>(per_chunk * 4)) return run_device<M, 4>(vehicles, drivers, n, o, r);
    }
    run_device<M, 1>(vehicles, drivers, n, o, r);
  });
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.failed = count_failed(r);
}

long gpu_batch_capacity_cuda(RomModel model) {
  int count = 0;
  if (cudaGetDeviceCount(&count) != cudaSuccess || count == 0) return 0;
  long runs = 0;
  with_model(model, [&](auto m) {
    // Threads that fit on an SM at the single-lane kernel's registers, asked in two-warp blocks (an
    // SM takes at most 32 blocks: one-warp blocks would cap it at 1,024 threads).
    int per_sm = 0;
    TERRACAL_CUDA_CHECK(cudaOccupancyMaxActiveBlocksPerMultiprocessor(
        &per_sm, parallel_for_kernel<BatchKernel<decltype(m), 1>>, 64, 0));
    runs = 64L * per_sm * cuda_sm_count();
  });
  return runs;
}

}  // namespace terracal::rom
