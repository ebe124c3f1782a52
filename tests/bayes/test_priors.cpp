// Priors files override the defaults -- bounds, normal and lognormal priors,
// fixed parameters -- and both the MAP point and the posterior obey them.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "bayes/calibrator.hpp"
#include "bayes/synthetic_data.hpp"
#include "core/errors.hpp"

using namespace terracal;
using namespace terracal::bayes;

namespace {
std::string priors_file(const std::string& text) {
  const auto path =
      std::filesystem::temp_directory_path() / ("terracal_priors_" + std::to_string(::getpid()) + ".json");
  std::ofstream(path) << text;
  return path.string();
}
const ParamVector kTruth = {990, 1528430, 1.1, 1040, 28, 0.01};
}  // namespace

TEST_CASE("priors file: kinds, names and validation", "[bayes][priors]") {
  const Priors p = load_priors(priors_file(R"({"Bekker Kphi": {"type": "uniform", "lower": 1e5, "upper": 1e8},
      "n": {"type": "normal", "mean": 1.0, "sd": 0.2}, "k": {"type": "lognormal", "mean": -4.6, "sd": 0.5},
      "Kc": {"type": "fixed", "value": 0}})"));
  CHECK(p[kKphi].lower == 1e5);
  CHECK(p[kKphi].upper == 1e8);
  CHECK(p[kN].kind == Prior::Kind::kNormal);
  CHECK(p[kN].log_density(1.2) == Approx(-0.5));
  CHECK(p[kJanosi].log_density(std::exp(-4.6)) == Approx(4.6));  // -log k at the log-mean
  CHECK(p[kKc].fixed());
  CHECK(p[kCohesion].kind == Prior::Kind::kUniform);  // untouched: the default
  CHECK_THROWS_AS(load_priors(priors_file(R"({"n": {"type": "normal", "mean": 1, "sd": 0}})")), InputError);
  CHECK_THROWS_AS(load_priors(priors_file(R"({"n": {"type": "fixed", "value": 2.5}})")), InputError);
  CHECK_THROWS_AS(load_priors(priors_file(R"({"n": {"type": "beta"}})")), InputError);
  CHECK_THROWS_AS(load_priors(priors_file(R"({"c": {"type": "uniform", "lower": 10, "upper": 5}})")), InputError);
  CHECK_THROWS_AS(load_priors(priors_file("{not json")), InputError);
}

TEST_CASE("a fixed parameter stays fixed and an informative prior moves the posterior", "[bayes][priors]") {
  SyntheticDesign d;
  Rng rng(21);
  const PlateData plate = synthesize_plate(kTruth, d, rng);
  const ShearData shear = synthesize_shear(kTruth, d, rng);
  // phi: a tight normal prior 2 degrees away from the truth, much tighter than the data; k fixed.
  const Priors priors = load_priors(priors_file(R"({"phi": {"type": "normal", "mean": 26.0, "sd": 0.01},
                                                    "k": {"type": "fixed", "value": 0.011}})"));
  const CalibrationProblem pb(plate, shear, priors);
  REQUIRE(pb.dim() == 5);
  CalibrationOptions opt;
  opt.min_ess = 300;
  const CalibrationResult res = calibrate(pb, opt);
  REQUIRE(res.converged);
  CHECK(res.point.map[kJanosi] == 0.011);
  CHECK(res.point.map[kFriction] == Approx(26.0).margin(0.05));
  const auto phi_slot = std::find(res.names.begin(), res.names.end(), "phi") - res.names.begin();
  REQUIRE(phi_slot < res.num_params);
  CHECK(res.summary[phi_slot].mean == Approx(26.0).margin(0.05));
  CHECK(res.summary[phi_slot].sd < 0.02);
}

TEST_CASE("one plate size with a prior on Kc: the run samples the prior along the unidentified direction",
          "[bayes][priors]") {
  // Only K(r) = Kc/r + Kphi at r = 0.1 m is measured; Kc is then set by its prior alone, so the
  // posterior sd of Kc must equal the prior sd. (The least-squares covariance is singular here.)
  SyntheticDesign d;
  d.plate_radii = {0.1};
  Rng rng(8);
  const PlateData plate = synthesize_plate(kTruth, d, rng);
  const ShearData shear = synthesize_shear(kTruth, d, rng);
  const Priors priors = load_priors(priors_file(R"({"Kc": {"type": "normal", "mean": 0, "sd": 1000}})"));
  const CalibrationProblem pb(plate, shear, priors);
  REQUIRE(pb.dim() == 6);
  CalibrationOptions opt;
  opt.min_ess = 400;
  const CalibrationResult res = calibrate(pb, opt);
  REQUIRE(res.converged);
  CHECK(res.summary[kKc].sd == Approx(1000).epsilon(0.15));
  CHECK(std::abs(res.summary[kKc].mean) < 200);
  // K(0.1) itself is well measured whatever Kc is.
  CHECK(res.point.map[kKc] / 0.1 + res.point.map[kKphi] == Approx(kTruth[kKc] / 0.1 + kTruth[kKphi]).epsilon(0.05));
}
