// `terracal pipeline-rom` end to end, cut short (10 calibration draws per chain, 50 validation draws):
// every stage writes its outputs, the accuracy-cost table holds every model on both validation
// manoeuvres, the ROMs cost a small fraction of the full vehicle's wall time for errors of a
// fraction of the manoeuvre's yaw rate, and calibration against the full vehicle lowers the speed and
// yaw-rate errors on the manoeuvres it was not calibrated on.
#include <cmath>
#include <filesystem>
#include <map>

#include <catch2/catch.hpp>

#include "core/csv.hpp"
#include "tests/apps/cli_runner.hpp"

using namespace terracal;

TEST_CASE("terracal pipeline-rom: full vehicle, calibration, validation and the accuracy-cost table",
          "[cli][pipeline-rom]") {
  const test::ScratchDir dir("cli_pipeline_rom");
  const std::string out = dir.str() + "/p";
  const test::CliResult r =
      test::run_cli("pipeline-rom --out " + out + " --max-draws 10 --draws 50 --no-plots", dir.str());
  INFO(r.err);
  // Ten draws per chain cannot converge: exit 1, everything written all the same.
  CHECK(r.exit_code == 1);
  CHECK(r.out.find("calibration NOT converged") != std::string::npos);
  for (const char* f : {"report.md", "summary.json", "accuracy_cost.csv", "calibration/rom_params.json",
                        "calibration/posterior.h5", "validation/report.md", "full/dlc/trajectory.csv",
                        "full/turn/inputs.txt", "maneuvers/sine.json"})
    CHECK(std::filesystem::exists(out + "/" + f));
  const CsvTable t = CsvTable::read(out + "/accuracy_cost.csv");
  REQUIRE(t.rows() == 12);  // 2 manoeuvres x (full vehicle, 3 presets, calibrated, calibrated batch)
  std::map<std::string, double> full_cost;
  std::map<std::string, std::map<std::string, std::pair<double, double>>> err;  // manoeuvre -> model -> (vx, yaw rate)
  for (std::size_t i = 0; i < t.rows(); ++i)
    if (t.text(i, "model") == "full vehicle") full_cost[t.text(i, "maneuver")] = t.number(i, "wall_per_simulated_second");
  REQUIRE(full_cost.size() == 2);
  for (std::size_t i = 0; i < t.rows(); ++i) {
    const std::string model = t.text(i, "model"), m = t.text(i, "maneuver");
    if (model == "full vehicle" || model.find("batch") != std::string::npos) continue;
    INFO(m << ", " << model << ": vx RMSE " << t.number(i, "vx_rmse_m_s") << ", yaw-rate RMSE "
           << t.number(i, "yaw_rate_rmse_rad_s") << ", wall per simulated s " << t.number(i, "wall_per_simulated_second"));
    err[m][model] = {t.number(i, "vx_rmse_m_s"), t.number(i, "yaw_rate_rmse_rad_s")};
    // The manoeuvres' yaw rates reach 0.3-0.4 rad/s and their speeds 8-12 m/s: every ROM stays within
    // a fifth of the yaw rate and half a metre per second, for under 1 % of the full vehicle's time.
    CHECK(t.number(i, "yaw_rate_rmse_rad_s") < 0.08);
    CHECK(t.number(i, "vx_rmse_m_s") < 0.5);
    CHECK(t.number(i, "wall_per_simulated_second") < 0.01 * full_cost[m]);
  }
  // Calibrated on the training manoeuvres, the ROM's point estimate (least squares: the same whatever
  // the draw cap) follows the full vehicle closer than the preset on the two it did not see, in speed
  // and in yaw rate.
  for (const char* m : {"sine", "turn"}) {
    const auto preset = err[m]["18dof preset"], calibrated = err[m]["18dof calibrated"];
    INFO(m << ": vx RMSE preset " << preset.first << ", calibrated " << calibrated.first << "; yaw-rate RMSE preset "
           << preset.second << ", calibrated " << calibrated.second);
    CHECK(calibrated.first < preset.first);
    CHECK(calibrated.second < preset.second);
  }
}
