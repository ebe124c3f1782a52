#pragma once
// Every CUDA runtime call is checked: a failure throws RunError naming the call, file and line.
#include <string>

#include <cuda_runtime.h>

#include "core/errors.hpp"

#define TERRACAL_CUDA_CHECK(call)                                                                      \
  do {                                                                                                 \
    const cudaError_t terracal_err_ = (call);                                                          \
    if (terracal_err_ != cudaSuccess)                                                                  \
      throw ::terracal::RunError(std::string("CUDA error in ") + #call + " at " + __FILE__ + ":" +     \
                                 std::to_string(__LINE__) + ": " + cudaGetErrorString(terracal_err_)); \
  } while (0)
