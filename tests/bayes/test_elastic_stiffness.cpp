// SCM's elastic stiffness Ke from the unloading of plate-sinkage curves (docs/formats.md, "plate.csv":
// unload and reload rows fit Ke): an unload or reload branch of a plate of radius r
// follows F = pi r^2 Ke (z - z_p), one plastic sinkage z_p per branch, Ke shared by all.
#include <catch2/catch.hpp>

#include <cmath>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "../apps/cli_runner.hpp"
#include "bayes/calibration_problem.hpp"
#include "bayes/elastic_stiffness.hpp"
#include "bayes/forward_models.hpp"
#include "bayes/synthetic_data.hpp"
#include "core/errors.hpp"

using namespace terracal;
using namespace terracal::bayes;

namespace {

constexpr double kKe = 4e7;  // Pa/m, the truth of every synthetic cycle here
// Dry sand (Land Locomotion Lab), Wong's Table 2.3: Kc, Kphi, n, c, phi, k.
const ParamVector kSand = {990, 1528430, 1.1, 1040, 28, 0.01};

// Plates of 0.1 and 0.2 m loaded to 0.1 m, unloaded to lift-off and reloaded at 3 and 6 cm.
SyntheticDesign cycle_design(double noise) {
  SyntheticDesign d;
  d.plate_radii = {0.1, 0.2};
  d.max_sinkage = 0.1;
  d.plate_points = 20;
  d.unload_at = {0.03, 0.06};
  d.elastic_stiffness = kKe;
  d.unload_points = 8;
  d.relative_noise = noise;
  return d;
}

// Synthetic curves through the CSV file, so that phases and previous maxima come from load_plate_csv.
PlateData cycles_via_csv(const std::string& dir, double noise, std::uint64_t seed) {
  Rng rng(seed);
  const std::string path = dir + "/plate.csv";
  write_plate_csv(path, synthesize_plate(kSand, cycle_design(noise), rng));
  return load_plate_csv(path);
}

bool any_note_contains(const std::vector<std::string>& notes, const std::string& text) {
  for (const auto& n : notes)
    if (n.find(text) != std::string::npos) return true;
  return false;
}

PlateData plate_from_text(const std::string& dir, const std::string& text) {
  const std::string path = dir + "/plate.csv";
  test::write(path, text);
  return load_plate_csv(path);
}

}  // namespace

TEST_CASE("Ke and every plastic sinkage are recovered exactly from noise-free cycles of two plates",
          "[bayes][elastic]") {
  const test::ScratchDir dir("ke_exact");
  const ElasticFit fit = fit_elastic_stiffness(cycles_via_csv(dir.str(), 0.0, 1));
  REQUIRE(fit.fitted);
  CHECK(std::abs(fit.ke / kKe - 1) < 1e-6);
  CHECK(fit.sd < 1e-6 * kKe);
  // 2 plates x 2 cycles x (unload + reload); each unload ends with one lift-off row (F = 0), unused.
  REQUIRE(fit.branches.size() == 8);
  CHECK(fit.lift_off_rows == 4);
  CHECK(fit.rows == 4 * 7 + 4 * 7);
  CHECK(fit.dof == fit.rows - 9);
  // z_p = z_u - F_Bekker(z_u) / (pi r^2 Ke): the sinkage left once the elastic part springs back.
  for (double r : {0.1, 0.2})
    for (double zu : {0.03, 0.06}) {
      const double zp = zu - plate_force(r, zu, kSand[kKc], kSand[kKphi], kSand[kN]) / (kPi * r * r * kKe);
      int matches = 0;
      for (const auto& b : fit.branches) matches += b.radius == r && std::abs(b.plastic_sinkage - zp) < 1e-9;
      INFO("r = " << r << " m, unloaded at " << zu << " m: expected z_p = " << zp
                  << " m on its unload and reload branch");
      CHECK(matches == 2);
    }
}

TEST_CASE("with 1 % force noise Ke is within 5 % and its standard error is honest", "[bayes][elastic]") {
  const test::ScratchDir dir("ke_noise");
  const ElasticFit fit = fit_elastic_stiffness(cycles_via_csv(dir.str(), 0.01, 7));
  REQUIRE(fit.fitted);
  INFO("Ke = " << fit.ke << " +- " << fit.sd << " Pa/m");
  CHECK(std::abs(fit.ke / kKe - 1) < 0.05);
  CHECK(std::abs(fit.ke - kKe) < 3 * fit.sd);
  CHECK(fit.quantile(0.05) < fit.ke);
  CHECK(fit.quantile(0.95) > fit.ke);

  // One replicate cannot tell an honest sd from an inflated one: over 200 replicates the squared
  // z-scores (Ke - truth)/sd must average 1 (sd of that mean ~ 0.1), and the 90 % intervals cover.
  const int reps = 200;
  double z2 = 0;
  int covered = 0;
  for (int k = 0; k < reps; ++k) {
    Rng rng(100 + k);
    const ElasticFit f = fit_elastic_stiffness(synthesize_plate(kSand, cycle_design(0.01), rng));
    REQUIRE(f.fitted);
    const double z = (f.ke - kKe) / f.sd;
    z2 += z * z;
    covered += f.quantile(0.05) <= kKe && kKe <= f.quantile(0.95);
  }
  INFO("mean squared z-score " << z2 / reps << ", 90 % intervals covering: " << covered << " of " << reps);
  CHECK(z2 / reps > 0.7);
  CHECK(z2 / reps < 1.4);
  CHECK(covered >= 168);  // 90 % of 200 = 180, binomial sd 4.2
  CHECK(covered <= 192);
}

TEST_CASE("without unload rows Ke keeps Chrono's default and a note says it was not fitted", "[bayes][elastic]") {
  const test::ScratchDir dir("ke_none");
  std::string text = "plate_radius_m,sinkage_m,force_N\n";
  for (double r : {0.1, 0.2})
    for (double z : {0.01, 0.02, 0.04, 0.06, 0.08})
      text += fmt::format("{},{},{}\n", r, z, plate_force(r, z, kSand[kKc], kSand[kKphi], kSand[kN]));
  const CalibrationProblem pb(plate_from_text(dir.str(), text), std::nullopt, default_priors());
  CHECK_FALSE(pb.elastic().fitted);
  CHECK(pb.elastic().ke == kDefaultElasticStiffness);
  CHECK(any_note_contains(pb.notes(), "Elastic stiffness not fitted"));
}

TEST_CASE(
    "bad unloading data: short branches are ignored, a rising force or no spare row keeps the default, "
    "a deeper unload row is an input error",
    "[bayes][elastic]") {
  const test::ScratchDir dir("ke_bad");
  const std::string head =
      "plate_radius_m,sinkage_m,force_N,phase\n0.1,0.01,300,load\n0.1,0.02,650,load\n0.1,0.03,1000,load\n";
  // F = pi 0.1^2 4e7 (z - z_p) = 1.2566e6 N/m (z - 0.0292042 m) from the turning point at 3 cm; then
  // a second branch with a single row above lift-off.
  const std::string unload3 =
      "0.1,0.03,1000,unload\n0.1,0.0298,748.6726,unload\n0.1,0.0296,497.3452,unload\n0.1,0.0294,246.0178,unload\n";
  {
    const ElasticFit f = fit_elastic_stiffness(
        plate_from_text(dir.str(), head + unload3 + "0.1,0.04,1400,load\n0.1,0.039,900,unload\n0.1,0.038,0,unload\n"));
    REQUIRE(f.fitted);
    CHECK(f.branches.size() == 1);
    CHECK(any_note_contains(f.notes, "has 1 row(s) with force > 0"));
    CHECK(any_note_contains(f.notes, "branch ignored"));
    CHECK(f.ke == Approx(kKe).epsilon(0.01));
  }
  {  // The force rises as the plate rises: mislabelled phases, not a soil.
    const ElasticFit f = fit_elastic_stiffness(
        plate_from_text(dir.str(), head + "0.1,0.029,1100,unload\n0.1,0.028,1200,unload\n0.1,0.027,1300,unload\n"));
    CHECK_FALSE(f.fitted);
    CHECK(f.ke == kDefaultElasticStiffness);
    CHECK(any_note_contains(f.notes, "not positive"));
  }
  {  // Two rows on one branch fix the slope but leave nothing to estimate its error from.
    const ElasticFit f = fit_elastic_stiffness(
        plate_from_text(dir.str(), head + "0.1,0.0298,748.6726,unload\n0.1,0.0296,497.3452,unload\n"));
    CHECK_FALSE(f.fitted);
    CHECK(f.ke == kDefaultElasticStiffness);
    CHECK(any_note_contains(f.notes, "no degree of freedom"));
  }
  try {
    plate_from_text(dir.str(), head + "0.1,0.031,900,unload\n");
    FAIL("an unload row deeper than the deepest sinkage so far must be refused");
  } catch (const InputError& e) {
    const std::string what = e.what();
    CHECK(what.find(":5") != std::string::npos);
    CHECK(what.find("deeper than the deepest sinkage so far") != std::string::npos);
  }
}

TEST_CASE("terracal calibrate writes the fitted Ke into scm_params.json and the summary",
          "[bayes][elastic][calibrate]") {
  const test::ScratchDir scratch("ke_cli");
  const std::string dir = scratch.str();
  Rng rng(2026);
  write_plate_csv(dir + "/plate.csv", synthesize_plate(kSand, cycle_design(0.01), rng));
  const test::CliResult r =
      test::run_cli("calibrate --plate " + dir + "/plate.csv --out " + dir + "/out --min-ess 300 --no-plots", dir);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(test::read_file(dir + "/out/scm_params.json"));
  const double ke = j["Soil parameters"]["Elastic stiffness"].get<double>();
  CHECK(ke != kDefaultElasticStiffness);
  CHECK(ke == Approx(kKe).epsilon(0.05));
  const auto& post = j["Posterior"]["Elastic stiffness"];
  CHECK(post["mean"].get<double>() == ke);
  CHECK(post["sd"].get<double>() > 0);
  CHECK(std::abs(ke - kKe) < 3 * post["sd"].get<double>());
  CHECK(post["q05"].get<double>() < post["q50"].get<double>());
  CHECK(post["q50"].get<double>() < post["q95"].get<double>());
  CHECK(post["rhat"].is_null());
  CHECK(post["method"].get<std::string>().find("least squares") != std::string::npos);
  CHECK(j["Fit"]["elastic_stiffness"]["fitted"] == true);
  CHECK(j["Fit"]["elastic_stiffness"]["branches"].size() == 8);
  // The unload and reload rows stay out of the Bekker fit: n is still the loading curves' exponent.
  CHECK(j["Soil parameters"]["Bekker n exponent"].get<double>() == Approx(kSand[kN]).epsilon(0.05));
  CHECK(r.out.find("\n  Ke ") != std::string::npos);
  CHECK(r.out.find("separate linear problem") != std::string::npos);
  CHECK(test::read_file(dir + "/out/summary.txt") == r.out);

  // The same command on loading-only curves keeps the default and says so in the file.
  SyntheticDesign loading_only = cycle_design(0.01);
  loading_only.unload_at.clear();
  write_plate_csv(dir + "/loading.csv", synthesize_plate(kSand, loading_only, rng));
  const test::CliResult r2 =
      test::run_cli("calibrate --plate " + dir + "/loading.csv --out " + dir + "/out2 --min-ess 300 --no-plots", dir);
  INFO(r2.err);
  REQUIRE(r2.exit_code == 0);
  const auto j2 = nlohmann::json::parse(test::read_file(dir + "/out2/scm_params.json"));
  CHECK(j2["Soil parameters"]["Elastic stiffness"].get<double>() == kDefaultElasticStiffness);
  CHECK(j2["Posterior"]["Elastic stiffness"]["fixed"] == true);
  bool noted = false;
  for (const auto& n : j2["Fit"]["notes"])
    noted = noted || n.get<std::string>().find("Elastic stiffness not fitted") != std::string::npos;
  CHECK(noted);
  CHECK(r2.out.find("Ke         fixed at 4e+07") != std::string::npos);
}
