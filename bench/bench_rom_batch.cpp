// Vehicles simulated at real-time factor 1: batches of N reduced-order HMMWVs, 2 s simulated at a
// 1e-3 s half-implicit step, outputs reduced where they run (summary metrics only), on the GPU (and
// on the CPU for scale). The figure is the largest N whose wall time (launches and copies included)
// stays within the 2 s simulated. Two cases: all vehicles sharing one parameter set and driver, and
// every vehicle with its own parameters (mass and friction varied).
// Usage: bench_rom_batch [cuda|cpu] [max_vehicles=4e6]
//        bench_rom_batch cuda wave: one launch's time against the batch's size, at a calibrator's
//        shape (18-DOF, every run its own parameters, a 10 s manoeuvre): how many runs one launch
//        holds before it lasts longer (docs/decisions.md, "ROM calibration on a GPU").
//        bench_rom_batch [cuda|cpu] calib [runs]: the same runs as the calibrator's forward model
//        makes them (vx, yaw rate, roll and ay sampled at 100 Hz and compared with targets), against
//        stepping alone: what sampling and comparing cost.
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "rom/rom_batch.hpp"
#include "rom/rom_vehicle_json.hpp"

using namespace terracal;
using namespace terracal::rom;

namespace {

// Batches of 2,016 to 64,512 runs of the 18-DOF model with varied parameters over one 10 s
// manoeuvre (steering both ways, as a lane change), timed launch by launch.
void wave_sweep(const RomVehicle& base) {
  const DriverSeries d =
      DriverSeries::from_rows({0, 2, 3, 4, 5, 6, 10}, {0, 0, 0.3, -0.3, 0.3, 0, 0}, {0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5},
                              {0, 0, 0, 0, 0, 0, 0}, "wave inputs");
  BatchOptions o;
  o.end_time = 10.0;
  o.initial_speed = 10.0;
  o.model = RomModel::k18Dof;
  o.device = BatchDevice::kCuda;
  std::printf("one launch holds %ld runs of one thread each\n", gpu_batch_capacity(o.model));
  std::printf("%10s %12s %14s %16s\n", "runs", "wall [s]", "stepping [s]", "run-steps/s");
  for (long n : {2016L, 4032L, 8064L, 12096L, 16128L, 24192L, 32256L, 40320L, 64512L}) {
    std::vector<RomVehicle> vs(n, base);
    for (long i = 0; i < n; ++i) {
      vs[i].mass *= 0.9 + 0.2 * (i % 1000) / 1000.0;
      vs[i].friction = 0.5 + 0.5 * (i % 777) / 777.0;
    }
    run_rom_batch(vs, {&d}, n, o);  // warm-up: the device's buffers at this size
    const BatchResult r = run_rom_batch(vs, {&d}, n, o);
    std::printf("%10ld %12.3f %14.3f %16.3g\n", n, r.wall_seconds, r.stepping_seconds,
                n * (o.end_time / o.step) / r.stepping_seconds);
    std::fflush(stdout);
  }
}

// The wave manoeuvre's runs, varied as in wave_sweep, stepped alone and then sampled and compared as
// calibrate-rom's batches are (four channels at 100 Hz, a target row at every sample), three times each.
void calibrator_shape(const RomVehicle& base, BatchDevice device, long n) {
  const DriverSeries d =
      DriverSeries::from_rows({0, 2, 3, 4, 5, 6, 10}, {0, 0, 0.3, -0.3, 0.3, 0, 0}, {0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5},
                              {0, 0, 0, 0, 0, 0, 0}, "wave inputs");
  std::vector<RomVehicle> vs(n, base);
  for (long i = 0; i < n; ++i) {
    vs[i].mass *= 0.9 + 0.2 * (i % 1000) / 1000.0;
    vs[i].friction = 0.5 + 0.5 * (i % 777) / 777.0;
  }
  BatchOptions stepping;
  stepping.end_time = 10.0;
  stepping.initial_speed = 10.0;
  stepping.model = RomModel::k18Dof;
  stepping.device = device;
  BatchOptions compared = stepping;
  compared.output_rate = 100;
  compared.channels = {kChVx, kChYawRate, kChRoll, kChAy};
  BatchTargets t;
  const int samples = static_cast<int>(compared.end_time * compared.output_rate) + 1;
  for (int s = 0; s < samples; ++s) {
    t.s0.push_back(s);
    t.s1.push_back(s);
    t.w.push_back(0.0);
  }
  t.y.assign(compared.channels.size() * samples, 0.0);
  compared.targets = {&t};
  std::printf("%ld runs of 10 s, 18-DOF, own parameters, %s\n", n, device == BatchDevice::kCpu ? "cpu" : "cuda");
  std::printf("%-30s %14s %16s\n", "batch", "stepping [s]", "run-steps/s");
  for (int repeat = 0; repeat < 3; ++repeat)
    for (const BatchOptions* o : {&stepping, &compared}) {
      const BatchResult r = run_rom_batch(vs, {&d}, n, *o);
      std::printf("%-30s %14.3f %16.3g\n", o == &stepping ? "stepping alone" : "4 channels compared at 100 Hz",
                  r.stepping_seconds, n * (o->end_time / o->step) / r.stepping_seconds);
      std::fflush(stdout);
    }
}

}  // namespace

int main(int argc, char** argv) {
  const std::string device = argc > 1 ? argv[1] : "cuda";
  if (argc > 2 && std::string(argv[2]) == "wave") {
    wave_sweep(load_rom_vehicle("hmmwv"));
    return 0;
  }
  if (argc > 2 && std::string(argv[2]) == "calib") {
    calibrator_shape(load_rom_vehicle("hmmwv"), device == "cpu" ? BatchDevice::kCpu : BatchDevice::kCuda,
                     argc > 3 ? std::atol(argv[3]) : 8064);
    return 0;
  }
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
