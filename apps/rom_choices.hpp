#pragma once
// The choices the ROM commands share: the model names of --model and the batch device of --device.
#include <map>
#include <string>

#include <fmt/format.h>

#include "core/device_selftest.hpp"
#include "core/errors.hpp"
#include "rom/rom_batch.hpp"
#include "rom/rom_run.hpp"

namespace terracal::app {

inline const std::map<std::string, rom::RomModel> kRomModels = {
    {"11dof", rom::RomModel::k11Dof}, {"18dof", rom::RomModel::k18Dof}, {"24dof", rom::RomModel::k24Dof}};

// --device cpu|cuda|auto: auto takes the GPU when this build has CUDA and a device answers; cuda
// without a device is an InputError naming why.
inline rom::BatchDevice batch_device(const std::string& choice) {
  const CudaDeviceInfo gpu = cuda_device_info();
  if (choice == "cuda" && !gpu.available)
    throw InputError(fmt::format("--device cuda: no CUDA device available ({})", gpu.description));
  const bool cuda = choice == "cuda" || (choice == "auto" && rom::cuda_batch_available() && gpu.available);
  return cuda ? rom::BatchDevice::kCuda : rom::BatchDevice::kCpu;
}

}  // namespace terracal::app
