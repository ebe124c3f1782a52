// `terracal pipeline-rom` end to end, cut short (10 calibration draws per chain, 50 validation draws):
// every stage writes its outputs, the accuracy-cost table holds every model on both validation
// manoeuvres, and the ROMs cost a small fraction of the full vehicle's wall time for errors of a
// fraction of the manoeuvre's yaw rate.
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
  for (std::size_t i = 0; i < t.rows(); ++i)
    if (t.text(i, "model") == "full vehicle") full_cost[t.text(i, "maneuver")] = t.number(i, "wall_per_simulated_second");
  REQUIRE(full_cost.size() == 2);
  for (std::size_t i = 0; i < t.rows(); ++i) {
    const std::string model = t.text(i, "model"), m = t.text(i, "maneuver");
    if (model == "full vehicle" || model.find("batch") != std::string::npos) continue;
    INFO(m << ", " << model << ": vx RMSE " << t.number(i, "vx_rmse_m_s") << ", yaw-rate RMSE "
           << t.number(i, "yaw_rate_rmse_rad_s") << ", wall per simulated s " << t.number(i, "wall_per_simulated_second"));
    // The manoeuvres' yaw rates reach 0.3-0.4 rad/s: every ROM stays within a third of that. The
    // speed misses by up to 4 m/s on the sine (the ROM preset's powertrain differs from the full
    // vehicle's: results/pipeline_rom), well below the 12 m/s driven.
    CHECK(t.number(i, "yaw_rate_rmse_rad_s") < 0.12);
    CHECK(t.number(i, "vx_rmse_m_s") < 5);
    CHECK(t.number(i, "wall_per_simulated_second") < 0.01 * full_cost[m]);
  }
}
