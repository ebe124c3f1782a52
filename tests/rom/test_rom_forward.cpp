// The ROM as the calibrator's forward model: each parameter set's predictions are its own single
// run sampled at the reference's times (on the output grid exactly, between samples linearly); a
// parameter set that makes an invalid vehicle fails alone; the batch's own sums of squared
// differences are the predictions'; the GPU batch gives the CPU batch's log-likelihoods within 1e-9
// relative, through its predictions and through its own sums.
#include <cmath>

#include <catch2/catch.hpp>

#include "bayes/model_problem.hpp"
#include "core/errors.hpp"
#include "rom/rom_forward.hpp"
#include "tests/rom/rom_test_vehicles.hpp"
#include "tests/skip.hpp"

using namespace terracal;
using namespace terracal::rom;
using namespace terracal::rom::testing;

namespace {

DriverSeries step_steer() {
  return DriverSeries::from_rows({0, 0.5, 0.8, 2.0}, {0, 0, 0.4, 0.4}, {0.3, 0.3, 0.3, 0.3}, {0, 0, 0, 0});
}

// A reference with the given sample times; its values are placeholders (the forward model reads
// only the times, the driver and the initial speed).
RomReference reference(const std::string& name, std::vector<double> time, double speed,
                       DriverSeries driver = step_steer()) {
  RomReference r{.dir = name, .name = name, .driver = std::move(driver)};
  r.initial_speed = speed;
  r.time = std::move(time);
  for (int c = 0; c < kRomChannelCount; ++c) {
    r.has[c] = true;
    r.values[c].assign(r.time.size(), 0.0);
  }
  return r;
}

std::vector<double> grid(double dt, int n) {
  std::vector<double> t;
  for (int i = 0; i < n; ++i) t.push_back(i * dt);
  return t;
}

// A single run's channel c at time t, linear between its samples `dt` apart.
double sampled(const RomRunResult& r, RomChannel c, double t, double dt) {
  const auto value = [&](const RomSample& s) {
    return c == kRcVx ? s.vx : c == kRcYawRate ? s.yaw_rate : c == kRcRoll ? s.roll : s.ay;
  };
  const double u = t / dt;
  const std::size_t i = static_cast<std::size_t>(std::floor(u + 1e-9));
  const double w = std::max(0.0, u - double(i));
  if (w < 1e-9 || i + 1 >= r.samples.size()) return value(r.samples[std::min(i, r.samples.size() - 1)]);
  return (1 - w) * value(r.samples[i]) + w * value(r.samples[i + 1]);
}

// The 18-DOF HMMWV compared on vx, yaw rate, roll and ay, at a 1 ms step.
const std::vector<RomChannel> kChannels = {kRcVx, kRcYawRate, kRcRoll, kRcAy};
RomForward hmmwv_forward(const std::vector<RomReference>& refs, std::vector<std::string> params,
                         BatchDevice device = BatchDevice::kCpu, bool small_batches_on_cpu = true) {
  return RomForward(
      {hmmwv(), RomModel::k18Dof, std::move(params), kChannels, &refs, 1e-3, device, small_batches_on_cpu});
}

}  // namespace

TEST_CASE("rom forward: each parameter set's predictions are its own single run at the reference times",
          "[rom][forward]") {
  // "grid" and "short" share a rate and run as one batch, with their own drivers, initial speeds and
  // end times; "offgrid" runs as a second batch.
  const DriverSeries brake = DriverSeries::from_rows({0, 0.3, 0.8}, {0, -0.2, -0.2}, {0.2, 0, 0}, {0, 0.4, 0.4});
  const std::vector<RomReference> refs = {reference("grid", grid(0.02, 101), 10.0),
                                          reference("offgrid", grid(0.0237, 60), 6.0),
                                          reference("short", grid(0.02, 40), 4.0, brake)};
  const std::vector<RomChannel>& channels = kChannels;
  const RomForward f = hmmwv_forward(refs, {"tire_cornering_scale_front", "roll_stiffness_front"});
  const std::vector<std::vector<double>> params = {{1.0, 31000}, {0.7, 45000}, {1.6, 20000}};
  std::vector<std::vector<double>> out;
  f(params, out);
  REQUIRE(out.size() == 3);
  const std::size_t rows = refs[0].time.size() + refs[1].time.size() + refs[2].time.size();
  REQUIRE(f.rows_per_channel() == rows);
  for (std::size_t i = 0; i < params.size(); ++i) {
    REQUIRE(out[i].size() == channels.size() * rows);
    std::size_t first = 0;
    for (const RomReference& ref : refs) {
      // Sampled as the batch samples: the reference's spacing, a whole number of 1 ms steps.
      const double dt = ref.name == "offgrid" ? 0.024 : 0.02;
      RomRunOptions o = options(RomModel::k18Dof, ref.end_time() + dt, ref.initial_speed);
      o.output_rate = 1.0 / dt;
      const RomRunResult single = run(f.vehicle(params[i]), ref.driver, o);
      for (std::size_t c = 0; c < channels.size(); ++c)
        for (std::size_t r = 0; r < ref.time.size(); ++r) {
          INFO(ref.name << ", set " << i << ", channel " << kRomChannelNames[channels[c]] << ", t = " << ref.time[r]);
          const double got = out[i][c * rows + first + r];
          const double want = sampled(single, channels[c], ref.time[r], dt);
          // On the grid the batch's samples are the single run's to the bit; off it (0.0237 s
          // apart, sampled every 0.024 s) both interpolate the same samples.
          if (ref.name != "offgrid")
            CHECK(got == want);
          else
            CHECK(std::fabs(got - want) <= 1e-12 * (1 + std::fabs(want)));
        }
      first += ref.time.size();
    }
  }
  // The sets differ where they should: the softer front tires turn less.
  const std::size_t last_yaw = 1 * rows + refs[0].time.size() - 1;
  CHECK(out[1][last_yaw] < out[0][last_yaw]);
}

TEST_CASE("rom forward: a parameter set that makes an invalid vehicle fails alone", "[rom][forward]") {
  const std::vector<RomReference> refs = {reference("a", grid(0.05, 21), 8.0)};
  const RomForward f({hmmwv(), RomModel::k18Dof, {"cg_height"}, {kRcYawRate}, &refs, 1e-3, BatchDevice::kCpu});
  std::vector<std::vector<double>> out;
  // With its CG 5 m up the roll springs cannot hold the body (validate refuses the vehicle).
  f({{0.713}, {5.0}, {0.8}}, out);
  CHECK(out[0].size() == 21);
  CHECK(out[1].empty());
  CHECK(out[2].size() == 21);
  CHECK_THROWS_AS(RomForward({hmmwv(), RomModel::k18Dof, {"stiffness"}, {kRcVx}, &refs, 1e-3, BatchDevice::kCpu}),
                  InputError);
}

TEST_CASE("rom forward: the batch's own sums of squared differences are those of its predictions", "[rom][forward]") {
  // On the output grid, off it (interpolated), and two references of one rate in one batch; the
  // references' values are a made-up signal per channel.
  std::vector<RomReference> refs = {reference("grid", grid(0.02, 101), 10.0),
                                    reference("offgrid", grid(0.0237, 60), 6.0),
                                    reference("short", grid(0.02, 40), 4.0)};
  for (RomReference& r : refs)
    for (int c = 0; c < kRomChannelCount; ++c)
      for (std::size_t i = 0; i < r.time.size(); ++i) r.values[c][i] = 0.3 * c + std::sin(1.7 * r.time[i] + c);
  const std::vector<RomChannel>& channels = kChannels;
  const RomForward f = hmmwv_forward(refs, {"tire_cornering_scale_front", "cg_height"});
  // The last set's CG 5 m up makes an invalid vehicle: no sums.
  const std::vector<std::vector<double>> params = {{1.0, 0.713}, {0.7, 0.8}, {1.6, 0.6}, {1.0, 5.0}};
  std::vector<std::vector<double>> predicted, sums;
  f(params, predicted);
  f.sse(params, sums);
  REQUIRE(sums.size() == params.size());
  CHECK(sums[3].empty());
  for (std::size_t i = 0; i < 3; ++i) {
    REQUIRE(sums[i].size() == channels.size());
    for (std::size_t c = 0; c < channels.size(); ++c) {
      double want = 0;
      std::size_t row = 0;
      for (const RomReference& r : refs)
        for (std::size_t k = 0; k < r.time.size(); ++k, ++row) {
          const double d = r.values[channels[c]][k] - predicted[i][c * f.rows_per_channel() + row];
          want += d * d;
        }
      INFO("set " << i << ", channel " << kRomChannelNames[channels[c]]);
      CHECK(want > 1.0);
      CHECK(std::fabs(sums[i][c] - want) <= 1e-12 * want);
    }
  }
}

TEST_CASE("rom forward: GPU and CPU batches give the same log-likelihoods within 1e-9 relative",
          "[rom][forward][gpu]") {
  if (!test::cuda_device_or_skip("rom forward GPU/CPU log-likelihood")) return;
  // "a" and "c" run as one launch (one rate; their own drivers, speeds and lengths), "b" as another.
  const DriverSeries brake = DriverSeries::from_rows({0, 0.3, 0.8}, {0, -0.2, -0.2}, {0.2, 0, 0}, {0, 0.4, 0.4});
  std::vector<RomReference> refs = {reference("a", grid(0.02, 101), 10.0), reference("b", grid(0.05, 40), 5.0),
                                    reference("c", grid(0.02, 40), 4.0, brake)};
  const std::vector<RomChannel>& channels = kChannels;
  // Observations: the preset's predictions plus a deterministic wiggle.
  const RomForward cpu = hmmwv_forward(refs, {"tire_cornering_scale_front", "torque_scale"});
  // Every batch on the GPU, however small.
  const RomForward gpu = hmmwv_forward(refs, {"tire_cornering_scale_front", "torque_scale"}, BatchDevice::kCuda, false);
  std::vector<std::vector<double>> base;
  cpu({{1.0, 1.0}}, base);
  std::vector<bayes::ModelChannel> obs;
  for (std::size_t c = 0; c < channels.size(); ++c) {
    bayes::ModelChannel m{kRomChannelNames[channels[c]], kRomChannelUnits[channels[c]], {}, {}, {}, {"a", "b", "c"}};
    for (std::size_t r = 0; r < cpu.rows_per_channel(); ++r) {
      m.y.push_back(base[0][c * cpu.rows_per_channel() + r] + 0.01 * std::sin(0.7 * double(r)));
      m.x.push_back(double(r));
      m.curve.push_back(r < refs[0].time.size() ? 0 : r < refs[0].time.size() + refs[1].time.size() ? 1 : 2);
    }
    obs.push_back(m);
  }
  std::vector<bayes::ModelParameter> ps(2);
  ps[0] = {"tire_cornering_scale_front", "-", {}, 1.0};
  ps[1] = {"torque_scale", "-", {}, 1.0};
  for (auto& p : ps) {
    p.prior.lower = 0.2;
    p.prior.upper = 5;
  }
  const auto wrap = [](const RomForward& f) {
    return [fp = &f](const std::vector<Eigen::VectorXd>& xs, std::vector<std::vector<double>>& out) {
      std::vector<std::vector<double>> p;
      for (const auto& x : xs) p.emplace_back(x.data(), x.data() + x.size());
      (*fp)(p, out);
    };
  };
  bayes::ModelProblem on_cpu(ps, obs, wrap(cpu)), on_gpu(ps, obs, wrap(gpu)), gpu_sums(ps, obs, wrap(gpu));
  // The GPU's own sums compare with the references' values: make them the observations.
  for (std::size_t c = 0; c < channels.size(); ++c) {
    std::size_t row = 0;
    for (RomReference& r : refs)
      for (std::size_t k = 0; k < r.time.size(); ++k) r.values[channels[c]][k] = obs[c].y[row++];
  }
  const RomForward gpu_compare =
      hmmwv_forward(refs, {"tire_cornering_scale_front", "torque_scale"}, BatchDevice::kCuda, false);
  gpu_sums.set_batch_sse(
      [fp = &gpu_compare](const std::vector<Eigen::VectorXd>& xs, std::vector<std::vector<double>>& out) {
        std::vector<std::vector<double>> p;
        for (const auto& x : xs) p.emplace_back(x.data(), x.data() + x.size());
        fp->sse(p, out);
      });
  std::vector<Eigen::VectorXd> xs, nv(64, Eigen::VectorXd::Constant(4, 1e-3));
  for (int i = 0; i < 64; ++i) xs.push_back(Eigen::Vector2d(0.8 + 0.01 * i, 0.85 + 0.008 * i));
  std::vector<double> lc, lg, ls;
  on_cpu.target().log_density_batch(xs, nv, lc);
  on_gpu.target().log_density_batch(xs, nv, lg);
  gpu_sums.target().log_density_batch(xs, nv, ls);
  double worst = 0, worst_sums = 0;
  for (int i = 0; i < 64; ++i) {
    INFO("set " << i << ": " << lc[i] << " (CPU), " << lg[i] << " (GPU), " << ls[i] << " (GPU sums)");
    REQUIRE(std::isfinite(lc[i]));
    worst = std::max(worst, std::fabs(lg[i] - lc[i]) / std::fabs(lc[i]));
    worst_sums = std::max(worst_sums, std::fabs(ls[i] - lc[i]) / std::fabs(lc[i]));
  }
  INFO("largest relative difference " << worst << ", with the GPU's own sums " << worst_sums);
  CHECK(worst < 1e-9);
  CHECK(worst_sums < 1e-9);
}
