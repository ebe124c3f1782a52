// The batch against single runs: every vehicle of a CPU batch equals its own single half-implicit
// run; its channels are the trajectory's samples; the GPU batch of the same 1000 different vehicles
// agrees with the CPU batch within 1e-10 relative, in one launch and in chunks.
#include <cmath>

#include <catch2/catch.hpp>

#include "core/errors.hpp"
#include "rom/rom18.hpp"
#include "rom/rom_batch.hpp"
#include "tests/rom/rom_test_vehicles.hpp"
#include "tests/skip.hpp"

using namespace terracal;
using namespace terracal::rom;
using namespace terracal::rom::testing;

namespace {
// 1000 HMMWVs that differ in mass, friction, cornering stiffness and steering.
std::vector<RomVehicle> varied_vehicles(long n) {
  std::vector<RomVehicle> vs(n, hmmwv());
  for (long i = 0; i < n; ++i) {
    const double u = static_cast<double>(i) / n;
    vs[i].mass *= 0.8 + 0.4 * u;
    vs[i].friction = 0.4 + 0.6 * std::fmod(7.0 * u, 1.0);
    for (auto& t : vs[i].tire) t.y[0].df0 *= 0.9 + 0.2 * std::fmod(13.0 * u, 1.0);
    vs[i].max_steer *= 0.5 + std::fmod(3.0 * u, 1.0);
  }
  return vs;
}

DriverSeries lane_change() {
  return DriverSeries::from_rows({0, 0.5, 1.0, 1.5, 2.0}, {0, 0.3, -0.3, 0.1, 0}, {0.4, 0.6, 0.5, 0.5, 0.4},
                                 {0, 0, 0, 0.2, 0});
}

double relative(double a, double b) { return std::fabs(a - b) / std::max(1.0, std::fabs(b)); }
}  // namespace

TEST_CASE("rom batch: each CPU batch vehicle equals its own single run, channels are its samples", "[rom][batch]") {
  const auto vehicles = varied_vehicles(40);
  const DriverSeries d = lane_change();
  BatchOptions o;
  o.end_time = 2.0;
  o.initial_speed = 12.0;
  o.output_rate = 100;
  o.channels = {kChVx, kChYawRate, kChY, kChAy};
  const BatchResult b = run_rom_batch(vehicles, {&d}, 40, o);
  REQUIRE(b.samples == 201);
  CHECK(b.failed == 0);
  for (long i = 0; i < 40; i += 13) {
    const RomRunResult r = run(vehicles[i], d, options(RomModel::k18Dof, 2.0, 12.0));
    const RomSample& last = r.samples.back();
    CHECK(b.metrics[kMetX * 40 + i] == last.x);
    CHECK(b.metrics[kMetY * 40 + i] == last.y);
    CHECK(b.metrics[kMetVx * 40 + i] == last.vx);
    for (int s = 0; s < b.samples; s += 50) {
      CHECK(b.channels[(0 * b.samples + s) * 40 + i] == r.samples[s].vx);
      CHECK(b.channels[(1 * b.samples + s) * 40 + i] == r.samples[s].yaw_rate);
      CHECK(b.channels[(2 * b.samples + s) * 40 + i] == r.samples[s].y);
      CHECK(b.channels[(3 * b.samples + s) * 40 + i] == r.samples[s].ay);
    }
  }
}

TEST_CASE("rom batch: GPU and CPU batches of 1000 different vehicles agree within 1e-10 (11, 18, 24 DOF)",
          "[rom][batch][gpu]") {
  if (!test::cuda_device_or_skip("rom batch GPU/CPU agreement")) return;
  const long n = 1000;
  const auto vehicles = varied_vehicles(n);
  const DriverSeries d = lane_change();
  BatchOptions o;
  o.end_time = 2.0;
  o.initial_speed = 12.0;
  o.output_rate = 50;
  o.channels = {kChVx, kChAy};
  for (RomModel m : {RomModel::k11Dof, RomModel::k18Dof, RomModel::k24Dof}) {
    o.model = m;
    o.device = BatchDevice::kCpu;
    o.max_chunk = 0;
    const BatchResult cpu = run_rom_batch(vehicles, {&d}, n, o);
    for (long chunk : {0L, 300L}) {
      o.device = BatchDevice::kCuda;
      o.max_chunk = chunk;
      const BatchResult gpu = run_rom_batch(vehicles, {&d}, n, o);
      INFO(model_name(m) << ", chunk " << chunk << ", " << gpu.chunks << " launches on " << gpu.device);
      double worst = 0;
      for (std::size_t k = 0; k < cpu.final_state.size(); ++k)
        worst = std::max(worst, relative(gpu.final_state[k], cpu.final_state[k]));
      for (std::size_t k = 0; k < cpu.channels.size(); ++k)
        worst = std::max(worst, relative(gpu.channels[k], cpu.channels[k]));
      INFO("largest relative difference " << worst);
      CHECK(worst < 1e-10);
      CHECK(gpu.failed == cpu.failed);
    }
  }
}

TEST_CASE("rom batch: a GPU batch as large as one launch holds (one lane per run) equals the CPU's",
          "[rom][batch][gpu]") {
  // The calibrator's lookahead fills a launch to gpu_batch_capacity runs, past the four-lane kernel's
  // wave: this batch runs the one-lane kernel.
  if (!test::cuda_device_or_skip("rom batch at the GPU's capacity")) {
    CHECK(gpu_batch_capacity(RomModel::k18Dof) == 0);  // no device: nothing to fill
    return;
  }
  const long n = gpu_batch_capacity(RomModel::k18Dof);
  REQUIRE(n >= 64);
  CHECK(n % 64 == 0);
  const auto vehicles = varied_vehicles(n);
  const DriverSeries d = lane_change();
  BatchOptions o;
  o.model = RomModel::k18Dof;
  o.end_time = 1.0;
  o.initial_speed = 12.0;
  o.output_rate = 50;
  o.channels = {kChVx, kChAy};
  o.device = BatchDevice::kCpu;
  const BatchResult cpu = run_rom_batch(vehicles, {&d}, n, o);
  o.device = BatchDevice::kCuda;
  const BatchResult gpu = run_rom_batch(vehicles, {&d}, n, o);
  double worst = 0;
  for (std::size_t k = 0; k < cpu.channels.size(); ++k)
    worst = std::max(worst, relative(gpu.channels[k], cpu.channels[k]));
  INFO(n << " runs in " << gpu.chunks << " launch(es); largest relative difference " << worst);
  CHECK(gpu.chunks == 1);
  CHECK(worst < 1e-10);
  CHECK(gpu.failed == cpu.failed);
}

TEST_CASE("rom batch: a GPU batch of mixed manoeuvres equals the CPU's, zeros past each run's end included",
          "[rom][batch][gpu]") {
  if (!test::cuda_device_or_skip("rom batch GPU mixed manoeuvres")) return;
  const auto vehicles = varied_vehicles(64);
  const DriverSeries a = lane_change();
  const DriverSeries b = DriverSeries::from_rows({0, 1.0}, {0, 0.2}, {0.8, 0.8}, {0, 0});
  BatchOptions o;
  o.output_rate = 50;
  o.channels = {kChVx, kChYawRate};
  std::vector<const DriverSeries*> drivers;
  for (int i = 0; i < 64; ++i) {
    drivers.push_back(i < 32 ? &a : &b);
    o.initial_speeds.push_back(i < 32 ? 12.0 : 5.0);
    o.end_times.push_back(i < 32 ? 2.0 : 1.2);
  }
  o.device = BatchDevice::kCpu;
  const BatchResult cpu = run_rom_batch(vehicles, drivers, 64, o);
  // The GPU batch reuses its device buffers from call to call: a first batch of longer runs leaves
  // non-zero samples where the second's shorter runs end.
  BatchResult gpu;
  BatchOptions longer = o;
  longer.device = BatchDevice::kCuda;
  longer.end_times.assign(64, 2.0);
  longer.initial_speeds.assign(64, 12.0);
  run_rom_batch(vehicles, drivers, 64, longer, gpu);
  o.device = BatchDevice::kCuda;
  run_rom_batch(vehicles, drivers, 64, o, gpu);
  REQUIRE(gpu.channels.size() == cpu.channels.size());
  double worst = 0;
  long zeros = 0;
  for (std::size_t k = 0; k < cpu.channels.size(); ++k) {
    worst = std::max(worst, relative(gpu.channels[k], cpu.channels[k]));
    zeros += cpu.channels[k] == 0.0 && gpu.channels[k] == 0.0;
  }
  CHECK(worst < 1e-10);
  CHECK(zeros >= 2 * 32 * (101 - 61));  // the turn's runs end at sample 60 of 100
}

TEST_CASE("rom batch: per-driver initial speeds and end times run each vehicle as its own batch would",
          "[rom][batch]") {
  const auto vehicles = varied_vehicles(6);
  const DriverSeries a = lane_change();
  const DriverSeries b = DriverSeries::from_rows({0, 1.0}, {0, 0.2}, {0.8, 0.8}, {0, 0});
  BatchOptions o;
  o.output_rate = 50;
  o.channels = {kChVx, kChYawRate};
  // Runs 0-2 on the lane change from 12 m/s for 2 s, runs 3-5 on the turn from 5 m/s for 1.2 s.
  std::vector<const DriverSeries*> drivers = {&a, &a, &a, &b, &b, &b};
  o.initial_speeds = {12, 12, 12, 5, 5, 5};
  o.end_times = {2.0, 2.0, 2.0, 1.2, 1.2, 1.2};
  const BatchResult mixed = run_rom_batch(vehicles, drivers, 6, o);
  REQUIRE(mixed.samples == 101);  // the longest run's
  for (long i = 0; i < 6; ++i) {
    BatchOptions one = o;
    one.initial_speeds.clear();
    one.end_times.clear();
    one.initial_speed = o.initial_speeds[i];
    one.end_time = o.end_times[i];
    const BatchResult alone = run_rom_batch({vehicles[i]}, {drivers[i]}, 1, one);
    for (int m = 0; m < kBatchMetricCount; ++m) CHECK(mixed.metrics[m * 6 + i] == alone.metrics[m]);
    for (int c = 0; c < 2; ++c)
      for (int s = 0; s < alone.samples; ++s)
        CHECK(mixed.channels[(c * mixed.samples + s) * 6 + i] == alone.channels[c * alone.samples + s]);
  }
  // Per-driver values must come one per driver, and be usable.
  BatchOptions bad = o;
  bad.end_times.pop_back();
  CHECK_THROWS_AS(run_rom_batch(vehicles, drivers, 6, bad), InputError);
  bad = o;
  bad.end_times[2] = 0;
  CHECK_THROWS_AS(run_rom_batch(vehicles, drivers, 6, bad), InputError);
  bad = o;
  bad.initial_speeds[4] = std::nan("");
  CHECK_THROWS_AS(run_rom_batch(vehicles, drivers, 6, bad), InputError);
}

TEST_CASE("rom batch: a sample's ay is the right-hand side's at its state with the inputs at its time",
          "[rom][batch]") {
  // Steady tires answer the steering at once: straight until 0.999 s, the wheel turned at 1.0 s. The
  // sample at 1.0 s sees the turn (the state has not moved yet, the tires' slip angles have); the one
  // at 0.99 s does not. A sample taken from the next step's right-hand side (mid-run) and one with
  // its own (the run's end) give the same bits.
  RomVehicle v = hmmwv();
  v.effects &= ~kEffectTireRelaxation;
  const DriverSeries d =
      DriverSeries::from_rows({0, 0.999, 1.0, 2.0}, {0, 0, 0.5, 0.5}, {0.3, 0.3, 0.3, 0.3}, {0, 0, 0, 0});
  BatchOptions o;
  o.initial_speed = 12.0;
  o.output_rate = 100;
  o.channels = {kChAy};
  o.end_time = 1.5;
  const BatchResult mid = run_rom_batch({v}, {&d}, 1, o);
  o.end_time = 1.0;
  const BatchResult end = run_rom_batch({v}, {&d}, 1, o);
  REQUIRE(mid.samples == 151);
  REQUIRE(end.samples == 101);
  CHECK(std::fabs(mid.channels[99]) < 1e-9);
  CHECK(std::fabs(mid.channels[100]) > 0.5);
  CHECK(mid.channels[100] == end.channels[100]);
  const RomRunResult single = run(v, d, options(RomModel::k18Dof, 1.5, 12.0));
  CHECK(single.samples[100].ay == mid.channels[100]);
  // The right-hand side at the end state (1.0 s) with the inputs at 1.0 s (within round-off: this file
  // is built without the ROM library's FMA), and not with those of the step before.
  double dy[Rom18::kStates];
  RomAux now, before;
  Rom18::rhs(v, d.at(1.0), single.samples[100].gear - 1, end.final_state.data(), dy, &now, true);
  Rom18::rhs(v, d.at(0.999), single.samples[100].gear - 1, end.final_state.data(), dy, &before, true);
  CHECK(relative(now.ay, end.channels[100]) < 1e-12);
  CHECK(relative(before.ay, end.channels[100]) > 0.1);
}
