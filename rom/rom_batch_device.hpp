#pragma once
// The GPU side of run_rom_batch (rom_batch_cuda.cu); only built with CUDA.
#include <vector>

#include "rom/rom_batch.hpp"

namespace terracal::rom {

// Fills r (its arrays sized by configure_batch, its counters zero).
void run_rom_batch_cuda(const std::vector<RomVehicle>& vehicles, const std::vector<const DriverSeries*>& drivers, long n,
                        const BatchOptions& options, BatchResult& r);

// gpu_batch_capacity on the device (0 where none is present).
long gpu_batch_capacity_cuda(RomModel model);

}  // namespace terracal::rom
