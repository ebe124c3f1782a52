#pragma once
// Independent jobs on several threads at once. Used for CRM runs on a GPU: one small run (a wheel,
// an annulus) keeps only a fraction of the device busy, since each step is a chain of short kernels
// with a host round trip between stages; several runs, each on its own host thread and therefore on
// its own CUDA stream, fill each other's gaps.
#include <cstddef>
#include <functional>

namespace terracal {

// Calls job(i) for every i in [0, n), on up to `width` threads at once, and returns when all have
// ended. width <= 1 (or n <= 1): in order, on the calling thread, exactly as a plain loop. A job that
// throws stops the hand-out of later jobs; once the running ones have ended, the exception of the
// lowest failed index is rethrown, so that a failure reads the same as in the plain loop.
void run_concurrently(std::size_t n, int width, const std::function<void(std::size_t)>& job);

}  // namespace terracal
