// calibrate-rom on references made by the same ROM with known parameters plus noise: the 90 %
// intervals cover the truth at about their nominal rate over 20 seeded runs; rom_params.json loads
// as --vehicle with the MAP values in it; bad references and parameter files exit 2 naming what is
// wrong.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "apps/rom_calibration.hpp"
#include "core/rng.hpp"
#include "rom/rom_forward.hpp"
#include "rom/rom_vehicle_json.hpp"
#include "tests/apps/cli_runner.hpp"
#include "tests/apps/rom_references.hpp"
#include "tests/scratch_dir.hpp"

using namespace terracal;
using namespace terracal::test;

namespace {

const char* kSteer = "0 0 0.5 0\n0.6 0.35 0.5 0\n2.5 0.35 0.5 0\n";
const char* kAccel = "0 0 0.9 0\n1.5 0 0.9 0\n1.8 0 0 0.6\n2.5 0 0 0.6\n";
constexpr const double* kNoise = kRomRefNoise;  // vx, yaw rate, roll, ay

}  // namespace

TEST_CASE("calibrate-rom: the 90 % intervals cover known parameters in 80-98 % of 20 seeded runs",
          "[apps][calibrate-rom]") {
  ScratchDir dir("calibrate_rom_coverage");
  const std::vector<std::string> params = {"tire_cornering_scale_front", "tire_cornering_scale_rear", "torque_scale"};
  const std::vector<double> truth = {0.8, 1.25, 1.15};
  write(dir.str() + "/p.json",
        R"({"tire_cornering_scale_front": {"type": "uniform", "lower": 0.3, "upper": 3},
            "tire_cornering_scale_rear": {"type": "uniform", "lower": 0.3, "upper": 3},
            "torque_scale": {"type": "uniform", "lower": 0.5, "upper": 2}})");
  int covered = 0, intervals = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const std::string d = dir.str() + fmt::format("/s{}", seed);
    write_rom_reference(d, "steer", kSteer, rom::RomModel::k11Dof, params, truth, 2.5, seed, 1);
    write_rom_reference(d, "accel", kAccel, rom::RomModel::k11Dof, params, truth, 2.5, seed, 2);
    app::RomCalibrationSettings s;
    s.model = rom::RomModel::k11Dof;
    s.vehicle = "hmmwv";
    s.references = {d + "/steer", d + "/accel"};
    s.params_json = dir.str() + "/p.json";
    s.out = d + "/out";
    s.seed = seed;
    s.chains = 12;
    s.min_ess = 150;
    s.max_rhat = 1.02;
    s.global_points = 32;
    s.plots = false;
    std::filesystem::create_directories(s.out);
    const app::RomCalibrationOutcome r = app::run_rom_calibration(s);
    REQUIRE(r.result.converged);
    const nlohmann::json j = nlohmann::json::parse(read_file(s.out + "/rom_params.json"));
    for (std::size_t k = 0; k < params.size(); ++k) {
      const auto& p = j["Posterior"][params[k]];
      covered += p["q05"].get<double>() <= truth[k] && truth[k] <= p["q95"].get<double>();
      ++intervals;
    }
    if (seed == 1) {
      // rom_params.json loads as a vehicle with the MAP values in it.
      const rom::RomVehicle base = rom::load_rom_vehicle("hmmwv");
      const rom::RomVehicle v = rom::load_rom_vehicle(s.out + "/rom_params.json");
      CHECK(v.tire[0].y[0].df0 / base.tire[0].y[0].df0 ==
            Approx(j["Posterior"]["tire_cornering_scale_front"]["map"].get<double>()).epsilon(1e-12));
      CHECK(v.tire[1].y[1].df0 / base.tire[1].y[1].df0 ==
            Approx(j["Posterior"]["tire_cornering_scale_rear"]["map"].get<double>()).epsilon(1e-12));
      CHECK(v.powertrain.max_torque.y[3] / base.powertrain.max_torque.y[3] ==
            Approx(j["Posterior"]["torque_scale"]["map"].get<double>()).epsilon(1e-12));
      CHECK(j["Fit"]["noise_sd"]["yaw_rate"].get<double>() == Approx(kNoise[1]).epsilon(0.2));
      CHECK(std::filesystem::exists(s.out + "/posterior.h5"));
      CHECK(std::filesystem::exists(s.out + "/fit_steer.csv"));
    }
  }
  INFO(covered << " of " << intervals << " intervals cover the truth");
  CHECK(covered >= 0.80 * intervals);
  CHECK(covered <= 0.98 * intervals);
}

TEST_CASE("calibrate-rom: i-SIR (the GPU's default sampler, here on the CPU) finds Metropolis-Hastings' posterior",
          "[apps][calibrate-rom]") {
  ScratchDir dir("calibrate_rom_isir");
  const std::vector<std::string> params = {"tire_cornering_scale_front", "tire_cornering_scale_rear", "torque_scale"};
  const std::vector<double> truth = {0.8, 1.25, 1.15};
  write(dir.str() + "/p.json",
        R"({"tire_cornering_scale_front": {"type": "uniform", "lower": 0.3, "upper": 3},
            "tire_cornering_scale_rear": {"type": "uniform", "lower": 0.3, "upper": 3},
            "torque_scale": {"type": "uniform", "lower": 0.5, "upper": 2}})");
  write_rom_reference(dir.str(), "steer", kSteer, rom::RomModel::k11Dof, params, truth, 2.5, 7, 1);
  write_rom_reference(dir.str(), "accel", kAccel, rom::RomModel::k11Dof, params, truth, 2.5, 7, 2);
  // Metropolis-Hastings; i-SIR; i-SIR with three steps' proposals per batch (as on a GPU).
  const struct { int tries, lookahead; } runs[] = {{1, 0}, {16, 0}, {16, 3}};
  std::vector<nlohmann::json> post;
  for (const auto& run : runs) {
    app::RomCalibrationSettings s;
    s.model = rom::RomModel::k11Dof;
    s.vehicle = "hmmwv";
    s.references = {dir.str() + "/steer", dir.str() + "/accel"};
    s.params_json = dir.str() + "/p.json";
    s.out = dir.str() + fmt::format("/out{}_{}", run.tries, run.lookahead);
    s.seed = 7;
    s.chains = run.tries > 1 ? 8 : 12;
    s.tries = run.tries;
    s.lookahead = run.lookahead;
    s.min_ess = 400;
    s.global_points = 32;
    s.plots = false;
    std::filesystem::create_directories(s.out);
    const app::RomCalibrationOutcome r = app::run_rom_calibration(s);
    REQUIRE(r.result.converged);
    const nlohmann::json j = nlohmann::json::parse(read_file(s.out + "/rom_params.json"));
    CHECK(j["Fit"]["tries"].get<int>() == run.tries);
    CHECK(j["Fit"]["lookahead"].get<int>() == std::max(run.lookahead, 1));  // 0 on the CPU: 1
    post.push_back(j["Posterior"]);
  }
  // Each i-SIR posterior against Metropolis-Hastings': medians within a tenth of the 90 % interval's
  // width, and the widths within 15 %. An i-SIR that picked by pi instead of pi / q, or ignored the
  // current state, or a lookahead that reused or mis-weighed another step's proposals, would sample
  // another distribution (tests/bayes/test_independence.cpp shows by how much).
  for (std::size_t k = 1; k < post.size(); ++k)
    for (const auto& name : params) {
      const auto &a = post[0][name], &b = post[k][name];
      const double wa = a["q95"].get<double>() - a["q05"].get<double>();
      const double wb = b["q95"].get<double>() - b["q05"].get<double>();
      INFO(name << " (run " << k << "): medians " << a["q50"] << " and " << b["q50"] << ", widths " << wa << " and "
                << wb);
      CHECK(std::abs(a["q50"].get<double>() - b["q50"].get<double>()) < 0.1 * wa);
      CHECK(std::abs(wb - wa) < 0.15 * wa);
    }
}

TEST_CASE("bad input, calibrate-rom: references and parameter files", "[apps][calibrate-rom][bad-input]") {
  ScratchDir dir("calibrate_rom_bad");
  const std::string root = dir.str();
  std::filesystem::create_directories(root + "/ok");
  write(root + "/ok/inputs.txt", kSteer);
  write(root + "/ok/trajectory.csv", "time,vx,yaw_rate,ay\n0,6,0,0\n0.05,6,0,0\n0.1,6,0,0\n");
  std::filesystem::create_directories(root + "/noinputs");
  write(root + "/noinputs/trajectory.csv", "time,vx,yaw_rate,ay\n0,6,0,0\n0.05,6,0,0\n0.1,6,0,0\n");
  std::filesystem::create_directories(root + "/late");
  write(root + "/late/inputs.txt", kSteer);
  write(root + "/late/trajectory.csv", "time,vx,yaw_rate,ay\n0.5,6,0,0\n0.55,6,0,0\n0.6,6,0,0\n");
  std::filesystem::create_directories(root + "/noay");
  write(root + "/noay/inputs.txt", kSteer);
  write(root + "/noay/trajectory.csv", "time,vx,yaw_rate\n0,6,0\n0.05,6,0\n0.1,6,0\n");
  write(root + "/unknown.json", R"({"tire_stifness": {"type": "uniform", "lower": 0.5, "upper": 2}})");
  write(root + "/roll11.json", R"({"roll_stiffness_front": {"type": "uniform", "lower": 1e4, "upper": 1e5}})");
  write(root + "/overlap.json", R"({"roll_stiffness_total": {"type": "uniform", "lower": 1e4, "upper": 1e5},
                                     "roll_stiffness_front": {"type": "uniform", "lower": 1e4, "upper": 1e5}})");
  write(root + "/inverted.json", R"({"torque_scale": {"type": "uniform", "lower": 2, "upper": 0.5}})");
  write(root + "/friction.json", R"({"friction": {"type": "uniform", "lower": 0.5, "upper": 1}})");
  struct Case {
    std::string args, expect;
    bool roll_model = false;  // run the 18-DOF model (the one with roll parameters)
  };
  const std::string base = "calibrate-rom --model 11dof --vehicle hmmwv --out " + root + "/o ";
  const std::string base18 = "calibrate-rom --model 18dof --vehicle hmmwv --out " + root + "/o ";
  const std::vector<Case> cases = {
      {"--reference " + root + "/noinputs", "no inputs.txt"},
      {"--reference " + root + "/missing", "not a folder"},
      {"--reference " + root + "/late", "expected the first row at time 0"},
      {"--reference " + root + "/noay", "no column 'ay'"},
      {"--reference " + root + "/ok,," + root + "/ok", "an empty folder name"},
      {"--reference " + root + "/ok --params " + root + "/unknown.json", "unknown key 'tire_stifness'"},
      {"--reference " + root + "/ok --params " + root + "/roll11.json", "has no roll stiffness"},
      {"--reference " + root + "/ok --params " + root + "/inverted.json", "lower 2 must be below upper 0.5"},
      {"--reference " + root + "/ok --params " + root + "/friction.json", "unknown key 'friction'"},
      {"--reference " + root + "/ok --model 30dof", "30dof"},
      {"--reference " + root + "/ok --tries -3", "--tries: value -3 is outside [0, 100000]"},
      {"--reference " + root + "/ok --warmup -2", "--warmup: value -2 is outside [-1, 1000000]"},
      {"--reference " + root + "/ok --starts 0", "--starts: value 0 is outside [1, 100]"},
      {"--reference " + root + "/ok --delayed-acceptance maybe", "'maybe' is not one of auto|off|on"},
      {"--reference " + root + "/ok --delayed-acceptance on --tries 8",
       "--delayed-acceptance on: expected the independence sampler with Metropolis-Hastings"},
      {"--reference " + root + "/ok --delayed-acceptance on --sampler ensemble", "got --sampler ensemble"},
      {"--reference " + root + "/ok --params " + root + "/overlap.json",
       "'roll_stiffness_total' and 'roll_stiffness_front' set the same vehicle values", true},
  };
  for (const Case& c : cases) {
    const CliResult r = run_cli((c.roll_model ? base18 : base) + c.args, root);
    INFO(c.args << "\n" << r.err);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find(c.expect) != std::string::npos);
    CHECK(!std::filesystem::exists(root + "/o"));
  }
}
