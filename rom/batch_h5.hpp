#pragma once
// batch.h5: what a batch of reduced-order vehicles produced (rom_batch.hpp), float64 throughout:
//   /                    attributes model, vehicle, step [s], end_time [s], initial_speed [m/s],
//                        output_rate [1/s], vehicles, failed, seed, device (text where a name)
//   /time                [sample]: k / output_rate [s] (empty when no channel was sampled)
//   /parameters/<name>   [vehicle]: each varied parameter's drawn values (rom/batch_vary.hpp),
//                        attributes "units" and "distribution"; the group is empty without --vary
//   /summary/<metric>    [vehicle]: each of kBatchMetricNames, attribute "units"
//   /channels/<channel>  [vehicle][sample]: each channel of BatchOptions::channels, attribute "units"
//                        (BatchResult holds them [channel][sample][vehicle]: written transposed)
//   /final_state         [vehicle][state] (BatchResult holds it [state][vehicle])
// Identical input gives a byte-identical file (no timestamps), and the file appears under its
// final name only once complete (written to a temporary name in the same folder, then renamed).
#include <cstdint>
#include <string>

#include "rom/batch_vary.hpp"
#include "rom/rom_batch.hpp"

namespace terracal::rom {

struct BatchH5Info {
  std::string model;       // the root attribute "model"; empty: model_name(options.model)
  std::string vehicle;     // the base vehicle's preset name or file
  std::uint64_t seed = 0;  // the --vary seed (written whether or not anything was varied)
};

// `draws` may be null (nothing varied). Throws RunError naming `path` when the result's sizes
// disagree with its counts or the options' channels, the draws with the vehicle count, or an HDF5
// call fails; no file is left under `path` or a temporary name then.
void write_batch_h5(const std::string& path, const BatchResult& r, const BatchOptions& o, const VaryDraws* draws,
                    const BatchH5Info& info);

}  // namespace terracal::rom
