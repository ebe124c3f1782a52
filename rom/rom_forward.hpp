#pragma once
// The ROM as a calibrator's forward model: many parameter sets of one base vehicle, each run on
// every reference manoeuvre, as one batch for all references sampled at one rate (OpenMP threads,
// or one CUDA launch that lasts as long as the longest reference). The
// predictions are the batch's sampled channels, interpolated linearly at the reference's times.
#include <string>
#include <vector>

#include "rom/rom_batch.hpp"
#include "rom/rom_reference.hpp"
#include "rom/rom_vehicle.hpp"

namespace terracal::rom {

struct RomForwardSetup {
  RomVehicle base;
  RomModel model = RomModel::k18Dof;
  std::vector<std::string> parameters;  // names from vary_parameter_names(), the order of each parameter vector
  std::vector<RomChannel> channels;     // compared channels, in this order
  const std::vector<RomReference>* references = nullptr;
  double step = 1e-3;  // half-implicit step [s]
  BatchDevice device = BatchDevice::kCpu;
  // With device kCuda, batches of fewer than 8 runs per CPU thread run on the CPU (a GPU launch
  // lasts as long as its longest run, whatever the batch's size).
  bool small_batches_on_cpu = true;
};

struct RomForwardStats {
  long runs = 0;                // vehicle runs (parameter sets x references)
  double wall_seconds = 0;      // in the batches (run_rom_batch)
  double stepping_seconds = 0;  // of which stepping the vehicles
  double call_seconds = 0;      // in the forward model's calls: the batches, building the vehicles, resampling
};

class RomForward {
 public:
  // One call at a time (it keeps a call's batch for the next). Throws InputError for an unknown
  // parameter, a reference lacking a compared channel, or a reference whose sample spacing is not a
  // whole number of steps.
  explicit RomForward(RomForwardSetup setup);
  // out[i]: for params[i], every channel's rows over all references (channel-major, then reference,
  // then sample), or empty when the vehicle failed on some reference or its parameters are invalid.
  void operator()(const std::vector<std::vector<double>>& params, std::vector<std::vector<double>>& out) const;
  // out[i]: for params[i], each channel's sum over every reference's rows of (observed - predicted)^2,
  // the observed values being the references' own; empty where operator() gives an empty vector. The
  // sums of operator()'s predictions to round-off, but the batch compares its samples where it runs
  // (BatchTargets): a GPU step copies 4 numbers per run back instead of every sample.
  void sse(const std::vector<std::vector<double>>& params, std::vector<std::vector<double>>& out) const;
  // The vehicle of one parameter vector (the base with the values applied).
  RomVehicle vehicle(const std::vector<double>& p) const;
  const RomForwardSetup& setup() const { return s_; }
  const RomForwardStats& stats() const { return stats_; }
  std::size_t rows_per_channel() const { return rows_; }

 private:
  RomForwardSetup s_;
  // The vehicles of params (an invalid set: the base, its ok 0), and the references grouped by rate.
  std::vector<RomVehicle> vehicles_of(const std::vector<std::vector<double>>& params, std::vector<char>& ok) const;
  std::vector<std::vector<std::size_t>> groups() const;
  // One batch of every vehicle on every reference of `group`: predictions into out, or with
  // `compare` each run's sums added into out.
  void run_group(const std::vector<std::size_t>& group, const std::vector<RomVehicle>& vehicles,
                 std::vector<std::vector<double>>& out, std::vector<char>& ok, bool compare) const;

  std::vector<double> rate_;  // output rate per reference [Hz]
  std::vector<int> samples_;  // the batch's samples per reference
  std::vector<BatchTargets> targets_;  // per reference: its rows on the batch's samples, its values
  std::vector<std::size_t> first_row_;  // per reference: its first row in a channel's block
  // A call's batch and its result, kept for the next call: a GPU step's batch holds a few hundred MB.
  mutable std::vector<RomVehicle> all_;
  mutable BatchResult batch_;
  std::size_t rows_ = 0;
  mutable RomForwardStats stats_;
};

// The batch's channel for a compared channel.
BatchChannel batch_channel(RomChannel c);

}  // namespace terracal::rom
