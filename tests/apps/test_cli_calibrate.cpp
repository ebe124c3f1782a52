// The outputs of `terracal calibrate`: byte-identical for the same
// seed, resumable after a kill, and the single-plate case handled and reported.
#include <catch2/catch.hpp>

#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <thread>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "bayes/posterior_h5.hpp"
#include "cli_runner.hpp"
#include "core/gnuplot.hpp"
#include "lowfi/scm_soil.hpp"
#include "lowfi/scm_steady_wheel.hpp"
#include "tests/test_paths.hpp"

using namespace terracal::test;
namespace fs = std::filesystem;

namespace {

const char* kOutputs[] = {"scm_params.json", "posterior.h5",  "summary.txt",
                          "plate_fit.png",   "shear_fit.png", "pairs.png"};

std::string calibrate_args(const std::string& out, const std::string& extra = "") {
  return "calibrate --plate " + demo_data("plate.csv") + " --shear " + demo_data("shear.csv") + " --out " + out +
         " --seed 11 " + extra;
}

// The plots only where gnuplot is (the program warns and writes none without it).
void require_identical_outputs(const std::string& a, const std::string& b) {
  const bool plots = terracal::gnuplot_available();
  for (const std::string f : kOutputs) {
    if (!plots && f.ends_with(".png")) continue;
    INFO(f);
    REQUIRE(fs::exists(a + "/" + f));
    REQUIRE(read_file(a + "/" + f) == read_file(b + "/" + f));
  }
}

// wheel.csv rows of the steady SCM wheel (0.47 x 0.25 m, 108 kg) on `soil` with slip sinkage, at
// slips 0.1, 0.3, 0.5, 0.7; `wiggle`: a fixed multiplicative noise pattern per slip (none if empty).
std::string steady_wheel_csv(const terracal::lowfi::ScmSoil& soil, const std::vector<double>& wiggle = {}) {
  terracal::lowfi::ScmSteadyWheelOptions opt;
  opt.slip_sinkage = true;
  std::string csv = "slip,load_N,dbp_N,torque_Nm,sinkage_m\n";
  std::size_t k = 0;
  for (double s : {0.1, 0.3, 0.5, 0.7}) {
    const auto r = terracal::lowfi::scm_steady_wheel(soil, {0.47, 0.25}, 1059.48, s, opt);
    const double e = wiggle.empty() ? 0.0 : wiggle[k++];
    csv += fmt::format("{},{},{},{},{}\n", s, 1059.48, r.dbp * (1 + e), r.torque * (1 - e), r.sinkage * (1 + e));
  }
  return csv;
}

}  // namespace

TEST_CASE("calibrate writes the contract outputs, the same seed gives byte-identical files", "[cli][calibrate]") {
  const ScratchDir scratch("determinism");
  const std::string dir = scratch.str();
  const CliResult r1 = run_cli(calibrate_args(dir + "/a", "--min-ess 400"), dir);
  INFO(r1.err);
  REQUIRE(r1.exit_code == 0);
  const CliResult r2 = run_cli(calibrate_args(dir + "/b", "--min-ess 400"), dir);
  REQUIRE(r2.exit_code == 0);
  require_identical_outputs(dir + "/a", dir + "/b");
  CHECK(r1.out.find("R-hat") != std::string::npos);
  CHECK_FALSE(fs::exists(dir + "/a/.checkpoint.cbor"));

  // scm_params.json: Chrono's block at the MAP, the posterior summary, the fit.
  const auto j = nlohmann::json::parse(read_file(dir + "/a/scm_params.json"));
  CHECK(j["Type"] == "SCM");
  for (const char* key : {"Bekker Kphi", "Bekker Kc", "Bekker n exponent", "Mohr cohesive limit", "Mohr friction limit",
                          "Janosi shear coefficient", "Elastic stiffness", "Damping"})
    CHECK(j["Soil parameters"].contains(key));
  // The demo data set is dry sand with 2 % noise: the MAP is near the truth (truth.json).
  const auto truth = nlohmann::json::parse(read_file(demo_data("truth.json")))["Soil parameters"];
  CHECK(j["Soil parameters"]["Bekker n exponent"].get<double>() ==
        Approx(truth["Bekker n exponent"].get<double>()).epsilon(0.05));
  CHECK(j["Soil parameters"]["Mohr friction limit"].get<double>() ==
        Approx(truth["Mohr friction limit"].get<double>()).epsilon(0.05));
  const auto& kphi = j["Posterior"]["Bekker Kphi"];
  CHECK(kphi["q05"].get<double>() < kphi["q50"].get<double>());
  CHECK(kphi["q50"].get<double>() < kphi["q95"].get<double>());
  CHECK(kphi["rhat"].get<double>() < 1.01);
  CHECK(kphi["ess_bulk"].get<double>() >= 400);
  CHECK(j["Fit"]["seed"] == 11);
  CHECK(j["Fit"]["chains"] == 4);
  // Without wheel curves the set is Chrono's block alone: no slip sinkage fitted or reported.
  CHECK_FALSE(j.contains("Slip sinkage"));
  CHECK_FALSE(j["Posterior"].contains("Slip sinkage S"));

  // posterior.h5: read back by dimension name.
  const auto idata = terracal::bayes::read_inference_data_h5(dir + "/a/posterior.h5");
  bool found_kphi = false;
  for (const auto& g : idata.groups)
    for (const auto& v : g.variables)
      if (g.name == "posterior" && v.name == "Kphi") {
        found_kphi = true;
        CHECK(v.dims == std::vector<std::string>{"chain", "draw"});
        CHECK(v.shape[0] == 4);
        CHECK(v.shape[1] == j["Fit"]["draws"].get<std::size_t>());
      }
  CHECK(found_kphi);
}

TEST_CASE("a killed calibration resumes and ends with exactly the draws of an uninterrupted run",
          "[cli][calibrate][resume]") {
  const ScratchDir scratch("resume");
  const std::string dir = scratch.str();
  // A long run (high ESS target) so that the kill lands while sampling.
  const std::string extra = "--min-ess 6000 --no-plots";
  const CliResult full = run_cli(calibrate_args(dir + "/full", extra), dir);
  REQUIRE(full.exit_code == 0);

  const std::string out = dir + "/killed";
  const std::string checkpoint = out + "/.checkpoint.cbor";
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    const std::string log = dir + "/child.log";
    freopen(log.c_str(), "w", stderr);
    freopen("/dev/null", "w", stdout);
    execl(terracal::test::terracal_exe().c_str(), terracal::test::terracal_exe().c_str(), "calibrate", "--plate",
          demo_data("plate.csv").c_str(), "--shear", demo_data("shear.csv").c_str(), "--out", out.c_str(), "--seed",
          "11", "--min-ess", "6000", "--no-plots", nullptr);
    _exit(127);
  }
  // Wait for the checkpoint after warm-up and at least one block of draws (the file is replaced,
  // so its size grows), then kill the child without warning.
  std::uintmax_t first_size = 0;
  bool killed = false;
  for (int i = 0; i < 20000 && !killed; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    std::error_code ec;
    const auto size = fs::file_size(checkpoint, ec);
    if (ec) continue;
    if (first_size == 0)
      first_size = size;
    else if (size > first_size) {
      kill(child, SIGKILL);
      killed = true;
    }
  }
  int status = 0;
  waitpid(child, &status, 0);
  REQUIRE(killed);
  REQUIRE(WIFSIGNALED(status));
  REQUIRE(fs::exists(checkpoint));
  REQUIRE_FALSE(fs::exists(out + "/scm_params.json"));  // nothing under a final name yet

  // Copies of the killed run's folder with the checkpoint damaged: one byte flipped, cut short, replaced.
  const std::string good = read_file(checkpoint);
  auto damaged_copy = [&](const std::string& name, std::string bytes) {
    fs::copy(out, dir + "/" + name, fs::copy_options::recursive);
    std::ofstream(dir + "/" + name + "/.checkpoint.cbor", std::ios::binary) << bytes;
    return dir + "/" + name;
  };
  std::string flipped = good;
  flipped[good.size() / 2] = static_cast<char>(flipped[good.size() / 2] ^ 0x01);
  const std::vector<std::pair<std::string, std::string>> damaged = {
      {damaged_copy("flipped", flipped), "checksum mismatch"},
      {damaged_copy("cut", good.substr(0, good.size() - 100)), "cut off"},
      {damaged_copy("foreign",
                    "\xa2\x66"
                    "format"),
       "not a terracal checkpoint"}};
  // A temporary left by a writer that died (its process is gone) is removed by the next run.
  const pid_t gone = fork();
  if (gone == 0) _exit(0);
  waitpid(gone, nullptr, 0);
  const std::string stale = out + "/.scm_params.json.tmp." + std::to_string(gone);
  write(stale, "partial");

  const CliResult resumed = run_cli(calibrate_args(out, extra), dir);
  INFO(resumed.err);
  REQUIRE(resumed.exit_code == 0);
  CHECK(resumed.err.find("resuming from " + checkpoint) != std::string::npos);
  CHECK(resumed.err.find("removed") != std::string::npos);
  CHECK_FALSE(fs::exists(stale));
  for (const char* f : {"scm_params.json", "posterior.h5", "summary.txt"}) {
    INFO(f);
    CHECK(read_file(dir + "/full/" + f) == read_file(out + "/" + f));
  }
  // A damaged or foreign checkpoint is named and ignored: the run starts over and ends as the full run.
  for (const auto& [folder, why] : damaged) {
    const CliResult r = run_cli(calibrate_args(folder, extra), dir);
    INFO(folder << ": " << r.err);
    REQUIRE(r.exit_code == 0);
    CHECK(r.err.find("checkpoint " + folder + "/.checkpoint.cbor ignored, the calibration starts over") !=
          std::string::npos);
    CHECK(r.err.find(why) != std::string::npos);
    CHECK(read_file(dir + "/full/summary.txt") == read_file(folder + "/summary.txt"));
    CHECK_FALSE(fs::exists(folder + "/.checkpoint.cbor"));
  }
}

TEST_CASE("one plate size: Kc is fixed at 0, the run goes on and says so", "[cli][calibrate]") {
  const ScratchDir scratch("oneplate");
  const std::string dir = scratch.str();
  std::string plate = "plate_radius_m,sinkage_m,force_N\n";
  for (const auto& line : std::vector<std::string>{"0.1,0.01,310", "0.1,0.02,640", "0.1,0.04,1350", "0.1,0.06,2080",
                                                   "0.1,0.08,2790", "0.1,0.1,3600"})
    plate += line + "\n";
  write(dir + "/plate.csv", plate);
  const CliResult r =
      run_cli("calibrate --plate " + dir + "/plate.csv --out " + dir + "/out --min-ess 300 --no-plots", dir);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(r.err.find("only one plate radius") != std::string::npos);
  CHECK(r.out.find("Kc         fixed at 0") != std::string::npos);
  const auto j = nlohmann::json::parse(read_file(dir + "/out/scm_params.json"));
  CHECK(j["Soil parameters"]["Bekker Kc"] == 0.0);
  CHECK(j["Posterior"]["Bekker Kc"]["fixed"] == true);
  CHECK(j["Fit"]["notes"].size() >= 1);
}

TEST_CASE("hitting the draw cap is reported as not converged (exit 1, outputs written)", "[cli][calibrate]") {
  const ScratchDir scratch("cap");
  const std::string dir = scratch.str();
  const CliResult r = run_cli(calibrate_args(dir + "/out", "--max-draws 50 --no-plots"), dir);
  CHECK(r.exit_code == 1);
  CHECK(r.out.find("NOT converged: draw cap 50 per chain reached") != std::string::npos);
  CHECK(r.err.find("did not converge") != std::string::npos);
  const auto j = nlohmann::json::parse(read_file(dir + "/out/scm_params.json"));
  CHECK(j["Fit"]["converged"] == false);
  CHECK(j["Fit"]["draws"] == 50);
}

TEST_CASE("calibrate --wheel fits the slip sinkage with the soil, and the set drives SCM with it",
          "[cli][calibrate][wheel]") {
  const ScratchDir scratch("wheel");
  const std::string dir = scratch.str();
  // Wheel curves of the demo's soil (truth.json) with S = 2.5, from the steady SCM wheel, 1 % noise
  // in a fixed pattern; the wheel's geometry in the run.json beside them, as `terracal wheel` writes it.
  terracal::lowfi::ScmSoil truth = terracal::lowfi::read_scm_json(demo_data("truth.json"));
  truth.slip_sinkage.S = 2.5;
  const std::string csv = steady_wheel_csv(truth, {0.01, -0.008, 0.004, -0.012});
  fs::create_directories(dir + "/crm_wheel");
  std::ofstream(dir + "/crm_wheel/wheel.csv") << csv;
  std::ofstream(dir + "/crm_wheel/run.json")
      << R"({"terrain": "crm", "wheel": {"radius": 0.47, "width": 0.25, "mass": 108, "angular_velocity": 1.0}})";

  const CliResult r =
      run_cli(calibrate_args(dir + "/fit", "--min-ess 200 --wheel " + dir + "/crm_wheel/wheel.csv"), dir);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(read_file(dir + "/fit/scm_params.json"));
  REQUIRE(j.contains("Slip sinkage"));
  CHECK(j["Slip sinkage"]["Model"] == "Lyasko");
  CHECK(j["Slip sinkage"]["S"].get<double>() == Approx(2.5).epsilon(0.1));
  const auto& s_post = j["Posterior"]["Slip sinkage S"];
  CHECK(s_post["q05"].get<double>() < 2.5);
  CHECK(s_post["q95"].get<double>() > 2.5);
  for (const char* key : {"wheel_dbp_N", "wheel_torque_Nm", "wheel_sinkage_m"}) CHECK(j["Fit"]["noise_sd"].contains(key));
  CHECK(j["Fit"]["wheel"]["radius_m"] == 0.47);
  // The set reads back with its slip sinkage, as `wheel --scm-effects slip_sinkage` will use it.
  CHECK(terracal::lowfi::read_scm_json(dir + "/fit/scm_params.json").slip_sinkage.S ==
        j["Slip sinkage"]["S"].get<double>());
  CHECK(r.out.find("wheel_sinkage") != std::string::npos);
  if (terracal::gnuplot_available())
    for (const char* png : {"wheel_dbp_fit.png", "wheel_torque_fit.png", "wheel_sinkage_fit.png"})
      CHECK(fs::exists(dir + "/fit/" + png));
}

TEST_CASE("calibrate --annulus-law scaled: the wheel's soil is the annulus's 1.5x stronger, and the outputs say so",
          "[cli][calibrate][wheel]") {
  const ScratchDir scratch("annulus_scaled");
  const std::string dir = scratch.str();
  // The demo's annulus curves come from truth.json; the wheel's soil is 1.5x as strong (c and tan phi)
  // and develops its shear over 4x the Janosi k. The MAP must find R near 1.5; the set keeps the
  // wheel's strength, and R and k_annulus appear only in the posterior and the fit's block.
  terracal::lowfi::ScmSoil wheel_soil = terracal::lowfi::read_scm_json(demo_data("truth.json"));
  const double R = 1.5;
  const double annulus_c = wheel_soil.cohesion, annulus_k = wheel_soil.janosi_k;
  wheel_soil.cohesion *= R;
  wheel_soil.friction_deg = std::atan(R * std::tan(wheel_soil.friction_deg * M_PI / 180)) * 180 / M_PI;
  wheel_soil.janosi_k *= 4;
  wheel_soil.slip_sinkage.S = 2.0;
  std::ofstream(dir + "/wheel.csv") << steady_wheel_csv(wheel_soil);
  std::ofstream(dir + "/wheel.json") << R"({"radius": 0.47, "width": 0.25, "mass": 108, "angular_velocity": 1.0})";
  const CliResult r = run_cli(calibrate_args(dir + "/fit", "--max-draws 50 --annulus-law scaled --wheel " + dir +
                                                              "/wheel.csv --wheel-spec " + dir + "/wheel.json"),
                              dir);
  INFO(r.err);
  REQUIRE((r.exit_code == 0 || r.exit_code == 1));  // 50 draws: converged or not, the outputs are written
  const auto j = nlohmann::json::parse(read_file(dir + "/fit/scm_params.json"));
  const auto& fit = j["Fit"]["annulus_law"];
  CHECK(fit["law"] == "scaled");
  CHECK(fit["strength_ratio_R"].get<double>() == Approx(R).epsilon(0.1));
  CHECK(fit["annulus_janosi_k_m"].get<double>() == Approx(annulus_k).epsilon(0.1));
  CHECK(j["Soil parameters"]["Mohr cohesive limit"].get<double>() == Approx(annulus_c * R).epsilon(0.15));
  CHECK(j["Posterior"].contains("Shear strength over annulus"));
  CHECK(j["Posterior"].contains("Annulus Janosi shear coefficient"));
  CHECK_FALSE(j["Soil parameters"].contains("Shear strength over annulus"));
  CHECK(read_file(dir + "/fit/summary.txt").find("law scaled") != std::string::npos);
}

TEST_CASE("calibrate --elastic-stiffness: the set and the wheel's model take the given Ke, the plates' fit is reported",
          "[cli][calibrate][wheel][elastic]") {
  const ScratchDir scratch("elastic_given");
  const std::string dir = scratch.str();
  // Wheel curves of the demo's soil with S = 2.0 and a rut that rebounds 10x softer than the demo's
  // Ke (its plates have no unloading, so their Ke is Chrono's default). Given that Ke, the MAP finds
  // S; the outputs carry the given Ke as the set's and the plates' value beside it.
  terracal::lowfi::ScmSoil soil = terracal::lowfi::read_scm_json(demo_data("truth.json"));
  soil.elastic_stiffness = 4e6;
  soil.slip_sinkage.S = 2.0;
  std::ofstream(dir + "/wheel.csv") << steady_wheel_csv(soil);
  std::ofstream(dir + "/wheel.json") << R"({"radius": 0.47, "width": 0.25, "mass": 108, "angular_velocity": 1.0})";
  const CliResult r = run_cli(calibrate_args(dir + "/fit", "--max-draws 50 --elastic-stiffness 4e6 --wheel " + dir +
                                                              "/wheel.csv --wheel-spec " + dir + "/wheel.json"),
                              dir);
  INFO(r.err);
  REQUIRE((r.exit_code == 0 || r.exit_code == 1));  // 50 draws: converged or not, the outputs are written
  const auto j = nlohmann::json::parse(read_file(dir + "/fit/scm_params.json"));
  CHECK(j["Soil parameters"]["Elastic stiffness"].get<double>() == 4e6);
  CHECK(j["Slip sinkage"]["S"].get<double>() == Approx(2.0).epsilon(0.05));
  const auto& post = j["Posterior"]["Elastic stiffness"];
  CHECK(post["fixed"] == true);
  CHECK(post["method"].get<std::string>().find("--elastic-stiffness") != std::string::npos);
  const auto& ke = j["Fit"]["elastic_stiffness"];
  CHECK(ke["given_Pa_m"].get<double>() == 4e6);
  CHECK(ke["plates_fit_Pa_m"].get<double>() == 4e7);
  CHECK(ke["fitted"] == false);
  CHECK(terracal::lowfi::read_scm_json(dir + "/fit/scm_params.json").elastic_stiffness == 4e6);
  CHECK(read_file(dir + "/fit/summary.txt").find("given by --elastic-stiffness") != std::string::npos);
}
