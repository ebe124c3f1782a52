#include "apps/memory_check.hpp"

#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/errors.hpp"

#ifdef TERRACAL_HAVE_CUDA
#include <cuda_runtime.h>
#endif

namespace terracal::app {

namespace {
constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;

// MemAvailable [bytes] of /proc/meminfo; negative when there is none.
double meminfo_available() {
  std::ifstream in("/proc/meminfo");
  std::string key, unit;
  double kib = 0;
  while (in >> key >> kib) {
    std::getline(in, unit);
    if (key == "MemAvailable:") return kib * 1024;
  }
  return -1;
}

// What a cgroup v2 limit leaves this container [bytes]; negative when it sets none.
double cgroup_available() {
  std::ifstream max("/sys/fs/cgroup/memory.max"), current("/sys/fs/cgroup/memory.current");
  std::string limit;
  double used = 0;
  if (!(max >> limit) || limit == "max" || !(current >> used)) return -1;
  try {
    return std::stod(limit) - used;
  } catch (const std::exception&) {
    return -1;
  }
}
}  // namespace

double available_host_bytes() {
  double avail = meminfo_available();
  if (avail < 0) avail = double(::sysconf(_SC_AVPHYS_PAGES)) * double(::sysconf(_SC_PAGESIZE));
  if (const double cg = cgroup_available(); cg >= 0) avail = std::min(avail, cg);
  return avail;
}

double available_gpu_bytes() {
#ifdef TERRACAL_HAVE_CUDA
  std::size_t free = 0, total = 0;
  if (cudaMemGetInfo(&free, &total) != cudaSuccess) return -1;
  return double(free);
#else
  return -1;
#endif
}

void check_memory(const std::string& subject, const std::string& what, double host_bytes, double gpu_bytes,
                  const std::string& expected, bool say) {
  const double host = available_host_bytes();
  const double gpu = gpu_bytes > 0 ? available_gpu_bytes() : -1;
  const bool host_short = host >= 0 && host_bytes > host, gpu_short = gpu >= 0 && gpu_bytes > gpu;
  if (!host_short && !gpu_short) {
    if (say)
      spdlog::info("memory: {} needs about {:.3g} GiB{} (estimated before allocating; {:.3g} GiB available{})", subject,
                   host_bytes / kGiB, gpu_bytes > 0 ? fmt::format(" and {:.3g} GiB on the GPU", gpu_bytes / kGiB) : "",
                   host / kGiB, gpu >= 0 ? fmt::format(", {:.3g} GiB free on the GPU", gpu / kGiB) : "");
    return;
  }
  const std::string need = gpu_short ? fmt::format("{:.3g} GiB of GPU memory", gpu_bytes / kGiB)
                                     : fmt::format("{:.3g} GiB of memory", host_bytes / kGiB);
  const std::string have = gpu_short ? fmt::format("{:.3g} GiB is free on the GPU", gpu / kGiB)
                                     : fmt::format("{:.3g} GiB is available", host / kGiB);
  throw InputError(fmt::format("{}: {} needs about {} where {}; expected {}", subject, what, need, have, expected));
}

void check_crm_memory(const CrmScene& scene, CrmDevice device, const std::string& subject, const std::string& expected,
                      bool say) {
  const CrmMemoryNeed n = crm_memory_need(scene, device);
  // crm_grid refuses more than 2e9 cells: the estimate counts that many, at least.
  const std::string what = fmt::format(
      "a CRM bin of {:.3g} x {:.3g} m filled {:.3g} m deep ({:.3g} particles, {:.3g} markers, {}{:.3g} cells)",
      scene.bin.size.x, scene.bin.size.y, scene.bin.fill_height, n.particles, n.markers, n.cells >= 2e9 ? "over " : "",
      n.cells);
  check_memory(subject, what, n.host_bytes, n.gpu_bytes, expected, say);
}

}  // namespace terracal::app
