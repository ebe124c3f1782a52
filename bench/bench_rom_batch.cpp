// Vehicles simulated at real-time factor 1: batches of N reduced-order HMMWVs, 2 s simulated at a
// 1e-3 s half-implicit step, outputs reduced where they run (summary metrics only), on the GPU (and
// on the CPU for scale). The figure is the largest N whose wall time (launches and copies included)
// stays within the 2 s simulated. Two cases: all vehicles sharing one parameter set and driver, and
// every vehicle with its own parameters (mass and friction varied).
// Usage: bench_rom_batch [cuda|cpu] [max_vehicles=4e6]
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "rom/rom_batch.hpp"
#include "rom/rom_vehicle_json.hpp"

using namespace terracal;
using namespace terracal::rom;

int main(int argc, char** argv) {
  const std::string device = argc > 1 ? argv[1] : "cuda";
  const long max_n = argc > 2 ? static_cast<long>(std::atof(argv[2])) : 4000000;
  const RomVehicle base = load_rom_vehicle("hmmwv");
  const DriverSeries d = DriverSeries::from_rows({0, 0.5, 1.0, 1.5, 2.0}, {0, 0.3, -0.3, 0.1, 0},
                                                 {0.4, 0.6, 0.5, 0.5, 0.4}, {0, 0, 0, 0, 0}, "bench inputs");
  BatchOptions o;
  o.end_time = 2.0;
  o.initial_speed = 12.0;
  o.device = device == "cpu" ? BatchDevice::kCpu : BatchDevice::kCuda;
  std::printf("%-6s %-8s %10s %10s %12s %10s %8s %s\n", "model", "params", "vehicles", "wall [s]", "veh*s/s",
              "B/vehicle", "failed", "device");
  for (RomModel m : {RomModel::k11Dof, RomModel::k18Dof, RomModel::k24Dof}) {
    o.model = m;
    for (bool varied : {false, true}) {
      for (long n = 10000; n <= max_n; n *= 2) {
        std::vector<RomVehicle> vs(varied ? n : 1, base);
        if (varied)
          for (long i = 0; i < n; ++i) {
            vs[i].mass *= 0.9 + 0.2 * (i % 1000) / 1000.0;
            vs[i].friction = 0.5 + 0.5 * (i % 777) / 777.0;
          }
        const BatchResult r = run_rom_batch(vs, {&d}, n, o);
        std::printf("%-6s %-8s %10ld %10.3f %12.3g %10.0f %8ld %s\n", model_name(m), varied ? "own" : "shared", n,
                    r.wall_seconds, n * o.end_time / r.wall_seconds, r.bytes_per_vehicle, r.failed, r.device.c_str());
        std::fflush(stdout);
        if (r.wall_seconds > 2.5 * o.end_time) break;
      }
    }
  }
  return 0;
}
