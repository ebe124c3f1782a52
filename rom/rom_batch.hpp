#pragma once
// Batches of independent reduced-order vehicles, one per thread: the same half-implicit step as a
// single run, looped with OpenMP on the CPU or as one CUDA thread per vehicle on the GPU (the
// pbrt-v4 pattern: rom_batch_kernel.hpp holds the loop body once). Each vehicle has its own
// parameters and driver (or shares them); outputs are reduced where the vehicles run: per-vehicle
// summary metrics, the final state, and chosen channels sampled at a chosen rate. Never a copy per
// step to the host. Vehicles beyond what the device memory holds at once run in chunks.
#include <string>
#include <vector>

#include "core/vehicle/driver_inputs.hpp"
#include "rom/rom_run.hpp"
#include "rom/rom_vehicle.hpp"

namespace terracal::rom {

enum class BatchDevice { kCpu, kCuda };

// Sampled channels, by name in batch.h5 ("channels/<name>").
enum BatchChannel : int { kChX, kChY, kChYaw, kChVx, kChVy, kChYawRate, kChAx, kChAy, kChRoll, kBatchChannelCount };
inline constexpr const char* kBatchChannelNames[] = {"x", "y", "yaw", "vx", "vy", "yaw_rate", "ax", "ay", "roll"};

// Per-vehicle summary metrics ("summary/<name>").
enum BatchMetric : int {
  kMetX,           // final x [m]
  kMetY,           // final y [m]
  kMetYaw,         // final yaw [rad]
  kMetVx,          // final forward speed [m/s]
  kMetMaxAy,       // largest |ay| [m/s^2]
  kMetMaxYawRate,  // largest |yaw rate| [rad/s]
  kMetMaxRoll,     // largest |roll| [rad] (0 for the 11-DOF model)
  kMetFailedAt,    // time the state diverged (the step too large) [s]; -1 when it did not
  kBatchMetricCount
};
inline constexpr const char* kBatchMetricNames[] = {"final_x",    "final_y",          "final_yaw",    "final_vx",
                                                    "max_abs_ay", "max_abs_yaw_rate", "max_abs_roll", "failed_at"};

// What a run is compared with, for a batch that returns each run's sum of squared differences per
// channel (BatchResult::sse) in place of its samples: a calibrator's GPU step then copies a few
// numbers per run instead of every sample. Row r, in time order, lies between the run's samples
// s0[r] and s1[r] (s1 = s0 + 1, or s0 at the last sample) at weight w[r] towards s1, as
// (1 - w) x[s0] + w x[s1]; y[c * rows + r] is its observed value of the batch's channel c.
struct BatchTargets {
  std::vector<int> s0, s1;
  std::vector<double> w, y;
  long rows() const { return static_cast<long>(w.size()); }
};

struct BatchOptions {
  RomModel model = RomModel::k18Dof;
  double step = 1e-3;          // half-implicit step [s]
  double end_time = 2.0;       // [s]
  double initial_speed = 0.0;  // [m/s]
  double output_rate = 0.0;    // channel samples per second; 0: summary metrics only
  std::vector<BatchChannel> channels;
  BatchDevice device = BatchDevice::kCpu;
  long max_chunk = 0;  // vehicles per launch; 0: as many as memory allows
  // Per driver (one entry per driver given), or empty: initial_speed and end_time for every vehicle.
  // Runs of different manoeuvres then share one launch, whose length is the longest run's instead
  // of the sum of all (a GPU thread steps one vehicle, so a launch lasts as long as its longest
  // run). Channel samples past a run's own end are left at 0.
  std::vector<double> initial_speeds, end_times;
  // Per driver (one entry per driver given), or empty: with them the batch returns BatchResult::sse
  // and no channel samples (output_rate and channels still set the samples compared).
  std::vector<const BatchTargets*> targets;
};

struct BatchResult {
  long vehicles = 0;
  int samples = 0;                  // channel samples per vehicle (time k / output_rate, k = 0..)
  std::vector<double> metrics;      // [metric][vehicle]
  std::vector<double> channels;     // [channel][sample][vehicle]
  std::vector<double> final_state;  // [state][vehicle]
  std::vector<double> sse;          // [channel][vehicle], with BatchOptions::targets
  int states = 0;
  long failed = 0;          // vehicles whose state diverged
  double wall_seconds = 0;      // the stepping, launches and copies included
  double stepping_seconds = 0;  // the stepping alone (on a GPU: from the launches to their end)
  std::string device;           // what ran it, in words
  long chunks = 0;
  double bytes_per_vehicle = 0;  // device memory per vehicle: parameters, driver, outputs
};

// `vehicles`: one (shared) or n; `drivers`: one (shared) or n. Throws InputError for mismatched
// sizes and RunError for CUDA failures or a GPU batch in a build without CUDA.
BatchResult run_rom_batch(const std::vector<RomVehicle>& vehicles, const std::vector<const DriverSeries*>& drivers,
                          long n, const BatchOptions& options);
// The same into `into`, whose arrays keep their memory from call to call: a caller that runs batch
// after batch of one size (the calibrator's forward model, a GPU launch per sampler step) then
// allocates and pages in nothing new (a few hundred MB of channel samples per launch).
void run_rom_batch(const std::vector<RomVehicle>& vehicles, const std::vector<const DriverSeries*>& drivers, long n,
                   const BatchOptions& options, BatchResult& into);

bool cuda_batch_available();

// How many runs of `model` one GPU launch holds at once, one thread per run: a batch up to this size
// lasts about one run's time. 0 without a CUDA device or in a build without CUDA.
long gpu_batch_capacity(RomModel model);

}  // namespace terracal::rom
