#include "rom/rom_batch.hpp"

#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "core/parallel_for.hpp"
#include "rom/rom_batch_kernel.hpp"
#include "rom/rom_models.hpp"
#if TERRACAL_HAVE_CUDA
#include "rom/rom_batch_device.hpp"
#endif

namespace terracal::rom {

namespace {

void check_batch(const std::vector<RomVehicle>& vehicles, const std::vector<const DriverSeries*>& drivers, long n,
                 const BatchOptions& o) {
  for (const RomVehicle& v : vehicles) check_model_effects(v, o.model);
  if (n < 1) throw InputError(fmt::format("--batch {}: expected at least 1 vehicle", n));
  if (vehicles.size() != 1 && static_cast<long>(vehicles.size()) != n)
    throw InputError(fmt::format("batch: {} parameter sets for {} vehicles (expected 1 or {})", vehicles.size(), n, n));
  if (drivers.size() != 1 && static_cast<long>(drivers.size()) != n)
    throw InputError(fmt::format("batch: {} drivers for {} vehicles (expected 1 or {})", drivers.size(), n, n));
  for (const auto* per : {&o.initial_speeds, &o.end_times})
    if (!per->empty() && per->size() != drivers.size())
      throw InputError(fmt::format("batch: {} per-driver {} for {} drivers (expected none or {})", per->size(),
                                   per == &o.end_times ? "end times" : "initial speeds", drivers.size(),
                                   drivers.size()));
  if (!o.targets.empty() && o.targets.size() != drivers.size())
    throw InputError(fmt::format("batch: {} target sets for {} drivers (expected none or {})", o.targets.size(),
                                 drivers.size(), drivers.size()));
  for (const BatchTargets* t : o.targets)
    if (o.output_rate <= 0 || o.channels.empty() || !t || t->s0.size() != t->w.size() || t->s1.size() != t->w.size() ||
        t->y.size() != t->w.size() * o.channels.size())
      throw InputError("batch: targets need an output rate, channels, and s0, s1, w and y for every row");
  for (double t : o.end_times)
    if (!(t > 0 && std::isfinite(t))) throw InputError(fmt::format("batch: end time {}: expected > 0 s", t));
  for (double v : o.initial_speeds)
    if (!std::isfinite(v)) throw InputError(fmt::format("batch: initial speed {}: expected a finite number", v));
  if (o.output_rate > 0 && std::fabs(std::round(1.0 / (o.output_rate * o.step)) * o.output_rate * o.step - 1.0) > 1e-9)
    throw InputError(fmt::format("--output-rate {} Hz: the output interval must be a whole number of steps of {} s",
                                 o.output_rate, o.step));
}

template <class M>
void run_cpu(const std::vector<RomVehicle>& vehicles, const std::vector<DriverSeriesView>& views, long n,
             const BatchOptions& o, BatchResult& r) {
  BatchKernel<M> k = configure_batch<M>(o, static_cast<long>(vehicles.size()), static_cast<long>(views.size()), n, r);
  k.vehicles = vehicles.data();
  k.drivers = views.data();
  std::vector<BatchTargetView> targets;
  for (const BatchTargets* t : o.targets)
    targets.push_back({t->s0.data(), t->s1.data(), t->w.data(), t->y.data(), t->rows()});
  if (!targets.empty()) k.targets = targets.data();
  const std::vector<long> steps = batch_steps(o);
  if (!o.end_times.empty()) k.driver_steps = steps.data();
  if (!o.initial_speeds.empty()) k.initial_speeds = o.initial_speeds.data();
  k.count = n;
  k.metrics = r.metrics.data();
  k.channels = r.channels.data();
  k.final_state = r.final_state.data();
  k.sse = r.sse.data();
  parallel_for_cpu(n, k);
  r.chunks = 1;
}

}  // namespace

bool cuda_batch_available() {
#if TERRACAL_HAVE_CUDA
  return true;
#else
  return false;
#endif
}

long gpu_batch_capacity(RomModel model) {
#if TERRACAL_HAVE_CUDA
  return gpu_batch_capacity_cuda(model);
#else
  (void)model;
  return 0;
#endif
}

BatchResult run_rom_batch(const std::vector<RomVehicle>& vehicles, const std::vector<const DriverSeries*>& drivers,
                          long n, const BatchOptions& o) {
  BatchResult r;
  run_rom_batch(vehicles, drivers, n, o, r);
  return r;
}

void run_rom_batch(const std::vector<RomVehicle>& vehicles, const std::vector<const DriverSeries*>& drivers, long n,
                   const BatchOptions& o, BatchResult& r) {
  check_batch(vehicles, drivers, n, o);
  r.failed = 0;
  r.chunks = 0;
  r.wall_seconds = r.stepping_seconds = r.bytes_per_vehicle = 0;
  if (o.device == BatchDevice::kCuda) {
#if TERRACAL_HAVE_CUDA
    run_rom_batch_cuda(vehicles, drivers, n, o, r);
    return;
#else
    throw RunError("rom batch: --device cuda, but this terracal was built without CUDA");
#endif
  }
  r.device = "cpu (OpenMP)";
  std::vector<DriverSeriesView> views;
  for (const DriverSeries* d : drivers) views.push_back(d->view());
  const auto start = std::chrono::steady_clock::now();
  with_model(o.model, [&](auto model) { run_cpu<decltype(model)>(vehicles, views, n, o, r); });
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.stepping_seconds = r.wall_seconds;
  r.failed = count_failed(r);
}

}  // namespace terracal::rom
