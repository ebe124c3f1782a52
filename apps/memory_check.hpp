#pragma once
// The memory a run needs against what this machine has, checked before the run allocates: a
// resolution that cannot fit is bad input (exit 2) naming the options that size it, where it would
// otherwise end in a std::bad_alloc naming nothing. The estimates live with their models
// (crm_memory_need in highfi/crm/crm_terrain.hpp, scm_memory_bytes in lowfi/scm_soil.hpp).
#include <string>

#include "highfi/crm/crm_terrain.hpp"

namespace terracal::app {

// Bytes this process can still allocate on the host: MemAvailable of /proc/meminfo (sysconf where
// there is none), within the container's cgroup limit when it has one.
double available_host_bytes();
// Free bytes of the current CUDA device; negative when unknown (no CUDA build, no device).
double available_gpu_bytes();

// Throws InputError "SUBJECT: WHAT needs about X GiB of memory (Y GiB on the GPU) where A GiB is
// available; expected EXPECTED" when either need is above what is available. `say`: when it fits,
// log the estimate and what is available (once per run, just before it allocates).
void check_memory(const std::string& subject, const std::string& what, double host_bytes, double gpu_bytes,
                  const std::string& expected, bool say = false);
// The same for a CRM scene run on `device` (its particles, markers and cells in WHAT).
void check_crm_memory(const CrmScene& scene, CrmDevice device, const std::string& subject, const std::string& expected,
                      bool say = false);

}  // namespace terracal::app
