// `pipeline` hands the rigs' curves to the calibrator in memory. The data set it builds must be the
// one the calibrator would read from the same rows written to plate.csv and shear.csv: the same
// points, phases, fitted rows and plate sizes, and the same refusals, naming the written file's line.
#include <catch2/catch.hpp>

#include <cmath>

#include "apps/calibration_run.hpp"
#include "core/errors.hpp"
#include "lowfi/scm_soil.hpp"
#include "tests/scratch_dir.hpp"

using namespace terracal;
using Catch::Matchers::Contains;

namespace {
// Equal to the 9 significant digits the curve files keep.
bool same(double memory, double file) { return std::abs(memory - file) <= 5e-9 * std::abs(memory) + 1e-300; }

// SCM plates with an unload-reload cycle and an annulus at two loads: every phase and both files.
app::BevameterCurves scm_curves() {
  app::SoilChoice soil;
  soil.solver = app::SoilModel::kScm;
  soil.scm = lowfi::reference_dry_sand();
  app::TerrainOptions o;
  o.grid = 0.01;
  app::BevameterPlan plan;
  plan.plates = {0.1, 0.2};
  plan.max_sinkage = 0.05;
  plan.shear_loads = {200, 400};
  plan.shear_angle = 0.3;
  plan.shear_settle = 0.3;
  return app::run_bevameter(soil, o, plan, true, true);
}
}  // namespace

TEST_CASE("calibration data from curves in memory equal the data read from the written curve files",
          "[apps][calibrate]") {
  test::ScratchDir dir("calibration_data");
  const app::BevameterCurves curves = scm_curves();
  rigs::write_plate_csv(dir.str() + "/plate.csv", curves.plate);
  rigs::write_shear_csv(dir.str() + "/shear.csv", curves.shear);
  const app::CalibrationData memory = app::calibration_data(curves, dir.str());
  const app::CalibrationData files =
      app::read_calibration_files({dir.str() + "/plate.csv", dir.str() + "/shear.csv", "", "", ""});

  REQUIRE(memory.plate.points.size() == files.plate.points.size());
  int unload = 0, fitted = 0;
  for (std::size_t i = 0; i < files.plate.points.size(); ++i) {
    const auto &m = memory.plate.points[i], &f = files.plate.points[i];
    INFO("plate row " << i);
    // The file holds 9 significant digits; in memory the calibrator sees the full doubles.
    CHECK(same(m.radius, f.radius));
    CHECK(same(m.sinkage, f.sinkage));
    CHECK(same(m.force, f.force));
    CHECK(m.phase == f.phase);
    CHECK(m.fitted == f.fitted);
    CHECK(m.line == f.line);
    unload += f.phase == bayes::PlatePhase::kUnload;
    fitted += f.fitted;
  }
  CHECK(unload > 0);  // the cycle is there, so the phase logic was exercised
  CHECK(fitted > 10);
  CHECK(memory.plate.radii == files.plate.radii);
  REQUIRE(memory.shear.has_value());
  REQUIRE(memory.shear->points.size() == files.shear->points.size());
  for (std::size_t i = 0; i < files.shear->points.size(); ++i) {
    const auto &m = memory.shear->points[i], &f = files.shear->points[i];
    INFO("shear row " << i);
    CHECK(same(m.angle, f.angle));
    CHECK(same(m.torque, f.torque));
    CHECK(same(m.normal_load, f.normal_load));
    CHECK(m.line == f.line);
  }
}

TEST_CASE("calibration data from curves in memory are refused as the files would be, naming the file and line",
          "[apps][calibrate][bad_input]") {
  app::BevameterCurves curves;
  curves.plate = {
      {0.1, 0.0, 0.0, "load"}, {0.1, 0.01, 100, "load"}, {0.1, 0.02, 180, "load"}, {0.1, 0.03, 150, "unload"}};
  try {
    app::calibration_data(curves, "out/bevameter");
    FAIL("no error");
  } catch (const InputError& e) {
    // The unload row (line 5 of the written file) is deeper than the plate has been.
    CHECK_THAT(e.what(), Contains("out/bevameter/plate.csv:5, column 'sinkage_m'") && Contains("deeper"));
  }
  curves.plate[3].phase = "press";
  CHECK_THROWS_AS(app::calibration_data(curves, "out/bevameter"), RunError);
}
