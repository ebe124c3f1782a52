// Plate phases and plate sizes as the calibrator sees them (docs/formats.md, "plate.csv"): the Bekker law is
// fitted to loading beyond the previous maximum sinkage, and only plates with such rows count. Every row is
// used or the file is refused naming the row: a plate's rows out of the order of its test are refused.
#include <catch2/catch.hpp>

#include <fstream>

#include "../scratch_dir.hpp"
#include "bayes/observations.hpp"

using namespace terracal;
using namespace terracal::bayes;

namespace {
// Writes a plate.csv with these rows, loads it as the calibrator does, and returns the data and the
// sinkages of the rows it fits.
PlateData load_rows(const std::string& name, const std::string& rows, std::vector<double>& fitted) {
  const test::ScratchDir dir(name);
  const std::string path = dir.str() + "/plate.csv";
  std::ofstream(path) << "plate_radius_m,sinkage_m,force_N,phase\n" << rows;
  PlateData d = load_plate_csv(path);
  fitted.clear();
  for (const auto& p : d.points)
    if (p.fitted) fitted.push_back(p.sinkage);
  return d;
}
}  // namespace

TEST_CASE("load / unload / reload: only loading beyond the previous maximum is fitted", "[bayes][observations]") {
  std::vector<double> fitted;
  const PlateData d = load_rows("phases",
                                "0.1,0.01,300,load\n0.1,0.02,650,load\n0.1,0.03,1000,load\n"
                                "0.1,0.025,400,unload\n0.1,0.02,100,unload\n"
                                "0.1,0.022,200,reload\n0.1,0.026,500,reload\n0.1,0.035,1200,reload\n"
                                "0.2,0.01,1100,\n0.2,0.02,2300,\n"
                                "0.3,0,0,load\n",  // a plate with no sinkage: no information
                                fitted);
  CHECK(fitted == std::vector<double>{0.01, 0.02, 0.03, 0.035, 0.01, 0.02});
  CHECK(d.radii == std::vector<double>{0.1, 0.2});
  REQUIRE(d.notes.size() == 1);  // the row at sinkage 0 is kept out of the fit, and that is said
  CHECK(d.notes[0].find("1 loading row(s) at sinkage 0") != std::string::npos);
}

TEST_CASE("a noisy reload that has rejoined the virgin curve stays on it until the next unload",
          "[bayes][observations]") {
  // A CRM plate's force jitters by a few percent: after the reload passes the old largest force
  // (1000 N), a row at 980 N is still virgin loading, not a one-row elastic branch.
  std::vector<double> fitted;
  load_rows("rejoin",
            "0.1,0.01,300,load\n0.1,0.02,650,load\n0.1,0.03,1000,load\n"
            "0.1,0.025,400,unload\n0.1,0.02,100,unload\n"
            "0.1,0.028,700,reload\n0.1,0.031,1010,reload\n0.1,0.032,980,reload\n0.1,0.033,1100,reload\n"
            "0.1,0.03,600,unload\n0.1,0.0335,900,reload\n",
            fitted);
  // The last reload row (900 N < 1100 N) follows a new unload: elastic again, not fitted.
  CHECK(fitted == std::vector<double>{0.01, 0.02, 0.03, 0.031, 0.032, 0.033});
}

TEST_CASE("values a hair below zero are noise, clearly negative ones a sign error", "[bayes][observations]") {
  std::vector<double> fitted;
  // A CRM plate starting at the surface: -3 N against 1000 N is noise around zero.
  const PlateData d = load_rows("zero_noise", "0.1,0.001,-3,load\n0.1,0.01,300,load\n0.1,0.03,1000,load\n", fitted);
  CHECK(d.points.size() == 3);
  std::vector<double> unused;
  CHECK_THROWS_WITH(load_rows("sign", "0.1,0.001,-30,load\n0.1,0.01,300,load\n0.1,0.03,1000,load\n", unused),
                    Catch::Contains("force_N") && Catch::Contains("-30") && Catch::Contains("negative"));
  // The annulus: round-off below zero at the first angle passes, a torque of the wrong sign does not.
  const test::ScratchDir dir("shear_zero_noise");
  const std::string path = dir.str() + "/shear.csv";
  const std::string head = "inner_radius_m,outer_radius_m,normal_load_N,angle_rad,torque_Nm\n";
  std::ofstream(path) << head << "0.1,0.2,98,0.001,-2.97e-16\n0.1,0.2,98,0.05,10\n0.1,0.2,98,0.1,12\n";
  CHECK(load_shear_csv(path).points.size() == 3);
  std::ofstream(path) << head << "0.1,0.2,98,0.001,-2\n0.1,0.2,98,0.05,10\n0.1,0.2,98,0.1,12\n";
  CHECK_THROWS_WITH(load_shear_csv(path), Catch::Contains("torque_Nm") && Catch::Contains("negative"));
}

TEST_CASE("plate rows out of the order of their test are refused naming the row, never dropped",
          "[bayes][observations]") {
  std::vector<double> fitted;
  const std::string in_order =
      "0.1,0.01,300,load\n0.1,0.02,650,load\n0.1,0.03,1000,load\n0.1,0.04,1400,load\n"
      "0.2,0.01,1100,load\n0.2,0.02,2300,load\n0.2,0.03,3600,load\n";
  const PlateData good = load_rows("order_good", in_order, fitted);
  CHECK(fitted.size() == 7);  // every loading row below the surface is fitted
  // Reversed and shuffled: refused at the first row that breaks the order, naming it and the row it contradicts.
  const std::string reversed =
      "0.1,0.04,1400,load\n0.1,0.03,1000,load\n0.1,0.02,650,load\n0.1,0.01,300,load\n"
      "0.2,0.03,3600,load\n0.2,0.02,2300,load\n0.2,0.01,1100,load\n";
  CHECK_THROWS_WITH(load_rows("order_reversed", reversed, fitted), Catch::Contains("plate.csv:3, column 'sinkage_m'") &&
                                                                       Catch::Contains("shallower than line 2") &&
                                                                       Catch::Contains("order of the test"));
  const std::string shuffled =
      "0.2,0.02,2300,load\n0.1,0.03,1000,load\n0.1,0.01,300,load\n0.2,0.01,1100,load\n"
      "0.1,0.04,1400,load\n0.2,0.03,3600,load\n0.1,0.02,650,load\n";
  CHECK_THROWS_WITH(load_rows("order_shuffled", shuffled, fitted),
                    Catch::Contains("plate.csv:4, column 'sinkage_m'") && Catch::Contains("shallower than line 3"));
  // Interleaved plates are fine: each plate's rows are in order; the data set is the grouped one.
  const std::string interleaved =
      "0.1,0.01,300,load\n0.2,0.01,1100,load\n0.1,0.02,650,load\n0.2,0.02,2300,load\n"
      "0.1,0.03,1000,load\n0.2,0.03,3600,load\n0.1,0.04,1400,load\n";
  const PlateData mixed = load_rows("order_interleaved", interleaved, fitted);
  REQUIRE(mixed.points.size() == good.points.size());
  for (std::size_t i = 0; i < good.points.size(); ++i) {
    CHECK(mixed.points[i].radius == good.points[i].radius);
    CHECK(mixed.points[i].sinkage == good.points[i].sinkage);
    CHECK(mixed.points[i].fitted == good.points[i].fitted);
  }
  // A hold (two rows at one sinkage) is loading too: both rows are fitted.
  load_rows("order_hold", "0.1,0.01,300,load\n0.1,0.02,650,load\n0.1,0.02,640,load\n0.1,0.03,1000,load\n", fitted);
  CHECK(fitted == std::vector<double>{0.01, 0.02, 0.02, 0.03});
}

TEST_CASE("unload and reload rows must follow the test's history", "[bayes][observations]") {
  std::vector<double> fitted;
  const std::string load = "0.1,0.01,300,load\n0.1,0.02,650,load\n0.1,0.03,1000,load\n";
  CHECK_THROWS_WITH(load_rows("reload_first", "0.1,0.01,300,load\n0.1,0.015,400,reload\n", fitted),
                    Catch::Contains("plate.csv:3, column 'phase'") && Catch::Contains("without an unload row"));
  CHECK_THROWS_WITH(load_rows("unload_sinks", load + "0.1,0.025,400,unload\n0.1,0.027,300,unload\n", fitted),
                    Catch::Contains("plate.csv:6") && Catch::Contains("deeper than the unload row before it (line 5"));
  CHECK_THROWS_WITH(
      load_rows("reload_rises", load + "0.1,0.02,100,unload\n0.1,0.025,500,reload\n0.1,0.022,300,reload\n", fitted),
      Catch::Contains("plate.csv:7") && Catch::Contains("shallower than the reload row before it"));
  // A row labelled load below the deepest sinkage after an unload was a reload: refused, not skipped.
  CHECK_THROWS_WITH(load_rows("load_after_unload", load + "0.1,0.02,100,unload\n0.1,0.025,500,load\n", fitted),
                    Catch::Contains("plate.csv:6") && Catch::Contains("label the rows with the phase column"));
}

TEST_CASE("shear rows at angle 0 are kept out of the data set and counted", "[bayes][observations]") {
  const test::ScratchDir dir("shear_at_rest");
  const std::string path = dir.str() + "/shear.csv";
  std::ofstream(path) << "inner_radius_m,outer_radius_m,normal_load_N,angle_rad,torque_Nm\n"
                      << "0.1,0.2,98,0,0\n0.1,0.2,98,0.05,10\n0.1,0.2,98,0.1,12\n0.1,0.2,196,0,0.1\n";
  const ShearData d = load_shear_csv(path);
  CHECK(d.points.size() == 2);
  REQUIRE(d.notes.size() == 1);
  CHECK(d.notes[0].find("2 row(s) at shear angle 0") != std::string::npos);
}
