// validate-rom: an 11-DOF ROM calibrated on one synthetic reference (known parameters plus noise)
// predicts another made with the same truth and noise: the 90 % predictive band covers 80-98 % of its
// samples per channel, the MAP's RMSE is the noise's sd within 30 % and beats the preset's on the yaw
// rate; the GPU gives the CPU's quantiles; bad inputs exit 2 naming the file or option.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "apps/rom_calibration.hpp"
#include "apps/rom_validation.hpp"
#include "core/rng.hpp"
#include "rom/rom_forward.hpp"
#include "rom/rom_vehicle_json.hpp"
#include "tests/apps/cli_runner.hpp"
#include "tests/apps/rom_references.hpp"
#include "tests/scratch_dir.hpp"
#include "tests/skip.hpp"

using namespace terracal;
using namespace terracal::test;

namespace {

const char* kSteer = "0 0 0.5 0\n0.6 0.35 0.5 0\n2.5 0.35 0.5 0\n";
// The validation manoeuvre: a steer to the right, back to the left, with a throttle change.
const char* kSlalom = "0 0 0.4 0\n0.5 -0.3 0.4 0\n1.5 -0.3 0.7 0\n2.0 0.3 0.7 0\n3.5 0.3 0.3 0\n4.0 0 0.3 0\n";
constexpr const double* kNoise = kRomRefNoise;  // vx, yaw rate, roll, ay
const std::vector<std::string> kParams = {"tire_cornering_scale_front", "tire_cornering_scale_rear", "torque_scale"};
const std::vector<double> kTruth = {0.8, 1.25, 1.15};

void write_reference(const std::string& dir, const std::string& name, const char* inputs, double end,
                     std::uint64_t seed, std::uint64_t stream) {
  write_rom_reference(dir, name, inputs, rom::RomModel::k11Dof, kParams, kTruth, end, seed, stream);
}

// The calibration of the first test case, once per process: DIR/cal (rom_params.json, posterior.h5),
// DIR/steer (fitted), DIR/slalom (validated on).
const std::string& calibrated(const std::string& dir) {
  static std::string done;
  if (!done.empty()) return done;
  write_reference(dir, "steer", kSteer, 2.5, 1, 1);
  write_reference(dir, "slalom", kSlalom, 4.5, 1, 3);
  write(dir + "/p.json",
        R"({"tire_cornering_scale_front": {"type": "uniform", "lower": 0.3, "upper": 3},
            "tire_cornering_scale_rear": {"type": "uniform", "lower": 0.3, "upper": 3},
            "torque_scale": {"type": "uniform", "lower": 0.5, "upper": 2}})");
  app::RomCalibrationSettings s;
  s.model = rom::RomModel::k11Dof;
  s.vehicle = "hmmwv";
  s.references = {dir + "/steer"};
  s.params_json = dir + "/p.json";
  s.out = dir + "/cal";
  s.seed = 1;
  s.chains = 12;
  s.min_ess = 150;
  s.max_rhat = 1.02;
  s.global_points = 32;
  s.plots = false;
  std::filesystem::create_directories(s.out);
  const app::RomCalibrationOutcome r = app::run_rom_calibration(s);
  REQUIRE(r.result.converged);
  done = dir;
  return done;
}

struct CalibratedDir {
  ScratchDir scratch{"validate_rom"};
  std::string dir = calibrated(scratch.str());
};
// One calibration shared by the test cases of this file (the scratch folder lives to the process's end).
const std::string& shared_dir() {
  static CalibratedDir d;
  return d.dir;
}

}  // namespace

TEST_CASE("validate-rom: the 90 % predictive band covers 80-98 % of a reference the ROM was not fitted to",
          "[apps][validate-rom]") {
  const std::string dir = shared_dir();
  app::RomValidationSettings s;
  s.posterior = dir + "/cal";
  s.references = {dir + "/slalom"};
  s.draws = 1000;
  s.out = dir + "/val_cpu";
  s.plots = gnuplot_available();
  const app::RomValidationOutcome o = app::run_rom_validation(s);
  REQUIRE(o.references.size() == 1);
  const auto& r = o.references[0];
  CHECK(o.model == "11dof");
  CHECK(o.seed == 1);  // the calibration's
  CHECK(r.failed_runs == 0);
  REQUIRE(r.channels.size() == 3);  // vx, yaw_rate, ay: the 11-DOF model has no roll
  for (const auto& c : r.channels) {
    const double noise = kNoise[c.channel];
    INFO(rom::kRomChannelNames[c.channel] << ": coverage " << c.coverage_predictive << " (model band "
                                          << c.coverage_model << "), RMSE MAP " << c.rmse_map << " median "
                                          << c.rmse_median << " preset " << c.rmse_preset << ", noise sd " << noise);
    CHECK(c.coverage_predictive >= 0.80);
    CHECK(c.coverage_predictive <= 0.98);
    CHECK(c.coverage_model <= c.coverage_predictive);
    CHECK(std::abs(c.rmse_map - noise) <= 0.3 * noise);
    if (c.channel == rom::kRcYawRate) CHECK(c.rmse_map < c.rmse_preset);
    for (std::size_t i = 0; i < r.time.size(); ++i) {
      CHECK(c.pred_q05[i] <= c.q05[i] + 1e-12);
      CHECK(c.q05[i] <= c.median[i]);
      CHECK(c.median[i] <= c.q95[i]);
      CHECK(c.q95[i] <= c.pred_q95[i] + 1e-12);
    }
  }
  // The files, and summary.json with the report's numbers.
  CHECK(std::filesystem::exists(s.out + "/report.md"));
  CHECK(std::filesystem::exists(s.out + "/band_slalom.csv"));
  if (s.plots) CHECK(std::filesystem::exists(s.out + "/band_slalom.png"));
  const nlohmann::json j = nlohmann::json::parse(read_file(s.out + "/summary.json"));
  CHECK(j["draws"] == 1000);
  CHECK(j["device"] == "cpu");
  const auto& yr = j["references"][0]["channels"]["yaw_rate"];
  CHECK(yr["rmse_map"].get<double>() == Approx(r.channels[1].rmse_map).epsilon(1e-12));
  CHECK(yr["coverage_predictive_90"].get<double>() == Approx(r.channels[1].coverage_predictive).epsilon(1e-12));
  CHECK(j["channels"]["yaw_rate"]["rmse_preset"].get<double>() == Approx(r.channels[1].rmse_preset).epsilon(1e-12));
  const std::string md = read_file(s.out + "/report.md");
  CHECK(md.find("| slalom | yaw_rate [rad/s] |") != std::string::npos);
  CHECK(md.find("without observation noise") != std::string::npos);
}

TEST_CASE("validate-rom: the GPU's quantiles are the CPU's within 1e-9", "[apps][validate-rom][cuda]") {
  if (!cuda_device_or_skip("validate-rom GPU twin")) return;
  const std::string dir = shared_dir();
  app::RomValidationSettings s;
  s.posterior = dir + "/cal";
  s.references = {dir + "/slalom", dir + "/steer"};
  s.draws = 1000;
  s.plots = false;
  s.out = dir + "/twin_cpu";
  const app::RomValidationOutcome cpu = app::run_rom_validation(s);
  s.device = rom::BatchDevice::kCuda;
  s.out = dir + "/twin_cuda";
  const app::RomValidationOutcome gpu = app::run_rom_validation(s);
  CHECK(gpu.device == "cuda");
  REQUIRE(gpu.references.size() == cpu.references.size());
  for (std::size_t k = 0; k < cpu.references.size(); ++k) {
    CHECK(gpu.references[k].failed_runs == cpu.references[k].failed_runs);
    for (std::size_t c = 0; c < cpu.references[k].channels.size(); ++c) {
      const auto& a = cpu.references[k].channels[c];
      const auto& b = gpu.references[k].channels[c];
      double scale = 0;  // the channel's size: quantiles near 0 (yaw rate at rest) are compared against it
      for (double v : a.q95) scale = std::max(scale, std::abs(v));
      const auto same = [&](const std::vector<double>& x, const std::vector<double>& y, const char* what) {
        REQUIRE(x.size() == y.size());
        double worst = 0;
        for (std::size_t i = 0; i < x.size(); ++i)
          worst = std::max(worst, std::abs(x[i] - y[i]) / std::max({std::abs(x[i]), std::abs(y[i]), 1e-6 * scale}));
        INFO(cpu.references[k].name << " " << rom::kRomChannelNames[a.channel] << " " << what << ": " << worst);
        CHECK(worst <= 1e-9);
      };
      same(a.q05, b.q05, "q05");
      same(a.median, b.median, "median");
      same(a.q95, b.q95, "q95");
      same(a.pred_q05, b.pred_q05, "predictive q05");
      same(a.pred_q95, b.pred_q95, "predictive q95");
      same(a.map, b.map, "MAP");
    }
  }
}

TEST_CASE("bad input, validate-rom: posterior files, references and --draws", "[apps][validate-rom][bad-input]") {
  const std::string dir = shared_dir();
  const std::string root = dir + "/bad";
  std::filesystem::create_directories(root + "/noparams");
  std::filesystem::copy_file(dir + "/cal/posterior.h5", root + "/noparams/posterior.h5");
  std::filesystem::create_directories(root + "/noh5");
  std::filesystem::copy_file(dir + "/cal/rom_params.json", root + "/noh5/rom_params.json");
  std::filesystem::create_directories(root + "/foreignh5");
  std::filesystem::copy_file(dir + "/cal/rom_params.json", root + "/foreignh5/rom_params.json");
  write(root + "/foreignh5/posterior.h5", "not an HDF5 file\n");
  std::filesystem::create_directories(root + "/noay");
  write(root + "/noay/inputs.txt", kSteer);
  write(root + "/noay/trajectory.csv", "time,vx,yaw_rate\n0,6,0\n0.05,6,0\n0.1,6,0\n");
  struct Case {
    std::string args, expect;
  };
  const std::string ref = " --reference " + dir + "/slalom --out " + root + "/o";
  const std::vector<Case> cases = {
      {"--posterior " + root + "/noparams" + ref, root + "/noparams/rom_params.json: not found"},
      {"--posterior " + root + "/noh5" + ref, root + "/noh5/posterior.h5: not found"},
      {"--posterior " + root + "/foreignh5" + ref, root + "/foreignh5/posterior.h5: not a posterior file"},
      {"--posterior " + dir + "/cal --reference " + root + "/noay --out " + root + "/o",
       root + "/noay/trajectory.csv: no column 'ay'"},
      {"--posterior " + dir + "/cal --draws 0" + ref, "--draws"},
      {"--posterior " + dir + "/cal --draws 100000000" + ref, "use --draws"},
  };
  for (const Case& c : cases) {
    const CliResult r = run_cli("validate-rom " + c.args, root);
    INFO(c.args << "\n" << r.err);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find(c.expect) != std::string::npos);
    CHECK(!std::filesystem::exists(root + "/o"));
  }
}
