// Joint calibration on bevameter and single-wheel curves: the steady SCM wheel as the wheel's forward
// model, Lyasko's S as a seventh parameter that only the wheel identifies.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include <omp.h>

#include "bayes/calibration_problem.hpp"
#include "bayes/point_estimate.hpp"
#include "bayes/synthetic_data.hpp"
#include "lowfi/scm_steady_wheel.hpp"

using namespace terracal;
using namespace terracal::bayes;

namespace {

// Dry sand (Wong's Table 2.3, k = 0.025 m) with the slip sinkage of CRM's wheels (S = 3).
ParamVector truth() { return {990, 1528430, 1.1, 1040, 28, 0.025, 3.0}; }

// The steady SCM wheel of `soil` at the given slips and loads, with multiplicative noise of sd `noise`.
// `ke`: the soil's elastic stiffness (by default the one that plate data without unloading leave in place).
WheelData synthesize_wheel(const ParamVector& p, const std::vector<double>& slips, const std::vector<double>& loads,
                           double noise, Rng& rng, double ke = kDefaultElasticStiffness) {
  lowfi::ScmSoil soil;
  soil.Kc = p[kKc], soil.Kphi = p[kKphi], soil.n = p[kN];
  soil.cohesion = p[kCohesion], soil.friction_deg = p[kFriction], soil.janosi_k = p[kJanosi];
  soil.elastic_stiffness = ke;
  soil.damping = kDefaultDamping;
  soil.slip_sinkage.S = p[kSlipSinkage];
  lowfi::ScmSteadyWheelOptions opt;
  opt.slip_sinkage = true;
  WheelData d;
  d.path = "synthetic wheel";
  d.wheel = {0.47, 0.25, 1.0};
  for (double load : loads)
    for (double s : slips) {
      const auto r = lowfi::scm_steady_wheel(soil, {0.47, 0.25}, load, s, opt);
      d.points.push_back({s, load, r.dbp * (1 + noise * rng.normal()), r.torque * (1 + noise * rng.normal()),
                          r.sinkage * (1 + noise * rng.normal()), 0});
    }
  return d;
}

double rel(double est, double truth) { return std::abs(est - truth) / std::abs(truth); }

}  // namespace

TEST_CASE("a joint calibration recovers S and the soil from bevameter and steady-wheel curves", "[bayes][wheel]") {
  Rng rng(31);
  const ParamVector t = truth();
  SyntheticDesign design;
  const PlateData plate = synthesize_plate(t, design, rng);
  const ShearData shear = synthesize_shear(t, design, rng);
  const WheelData wheel = synthesize_wheel(t, {0.1, 0.3, 0.5, 0.7}, {1059.48, 1600}, 0.02, rng);
  const CalibrationProblem problem(plate, shear, default_priors(), NoiseModel::kRelative, wheel);
  REQUIRE(problem.num_types() == 5);
  REQUIRE(std::count(problem.free_indices().begin(), problem.free_indices().end(), kSlipSinkage) == 1);

  // The model the problem predicts with is the steady wheel the data came from (no noise at the truth
  // but the data's own): its residuals at the truth are of the noise's size.
  const WheelPrediction& f = problem.predict_wheel(t);
  for (std::size_t i = 0; i < wheel.points.size(); ++i) {
    INFO("row " << i);
    CHECK(rel(f.sinkage[i], wheel.points[i].sinkage) < 0.08);
    CHECK(rel(f.torque[i], wheel.points[i].torque) < 0.08);
  }

  const PointEstimate est = estimate_point(problem, PointEstimateOptions{.seed = 5});
  const ParamVector& p = est.map;
  INFO("S " << p[kSlipSinkage] << ", Kphi " << p[kKphi] << ", n " << p[kN] << ", phi " << p[kFriction] << ", k "
            << p[kJanosi] << "\n"
            << est.ceres_report);
  CHECK(rel(p[kSlipSinkage], t[kSlipSinkage]) < 0.05);
  CHECK(rel(p[kN], t[kN]) < 0.05);
  CHECK(rel(p[kFriction], t[kFriction]) < 0.05);
  CHECK(rel(p[kJanosi], t[kJanosi]) < 0.05);
  for (double r : design.plate_radii) CHECK(rel(p[kKc] / r + p[kKphi], t[kKc] / r + t[kKphi]) < 0.05);
  CHECK(est.covariance_ok);
}

TEST_CASE("the wheel's slips evaluated at once give the predictions of one at a time, bit for bit",
          "[bayes][wheel][concurrent]") {
  Rng rng(7);
  const ParamVector t = truth();
  SyntheticDesign design;
  const PlateData plate = synthesize_plate(t, design, rng);
  const ShearData shear = synthesize_shear(t, design, rng);
  const WheelData wheel = synthesize_wheel(t, {0.0, 0.1, 0.2, 0.3, 0.5, 0.7, 0.8}, {1059.48}, 0.02, rng);
  const int threads = omp_get_max_threads();
  // Each problem keeps its own last prediction, so every call below is a fresh evaluation.
  auto predict = [&](int omp_threads, const ParamVector& p) {
    omp_set_num_threads(omp_threads);  // the slips' threads follow the OpenMP budget
    const CalibrationProblem problem(plate, shear, default_priors(), NoiseModel::kRelative, wheel);
    const WheelPrediction f = problem.predict_wheel(p);
    omp_set_num_threads(threads);
    return f;
  };
  const WheelPrediction serial = predict(1, t), at_once = predict(4, t);
  REQUIRE(serial.dbp.size() == wheel.points.size());
  for (std::size_t i = 0; i < serial.dbp.size(); ++i) {
    INFO("row " << i);
    CHECK(std::isfinite(serial.dbp[i]));
    CHECK(at_once.dbp[i] == serial.dbp[i]);
    CHECK(at_once.torque[i] == serial.torque[i]);
    CHECK(at_once.sinkage[i] == serial.sinkage[i]);
  }
  // A set with no steady state at some slips is rejected as a whole (NaN rows) either way.
  ParamVector soft = t;
  soft[kKphi] = 1e3, soft[kKc] = 1;
  const WheelPrediction soft_serial = predict(1, soft), soft_at_once = predict(4, soft);
  const auto any_nan = [](const WheelPrediction& f) {
    return std::any_of(f.dbp.begin(), f.dbp.end(), [](double x) { return std::isnan(x); });
  };
  REQUIRE(any_nan(soft_serial));
  CHECK(any_nan(soft_at_once));
}

TEST_CASE("wheel curves without shear curves leave c, phi and k free: the wheel's shear identifies them",
          "[bayes][wheel]") {
  Rng rng(34);
  const ParamVector t = truth();
  const PlateData plate = synthesize_plate(t, SyntheticDesign{}, rng);
  const WheelData wheel = synthesize_wheel(t, {0.1, 0.3, 0.5, 0.7}, {1059.48}, 0.02, rng);
  const CalibrationProblem with_wheel(plate, std::nullopt, default_priors(), NoiseModel::kRelative, wheel);
  CHECK(with_wheel.dim() == 7);
  const CalibrationProblem plate_only(plate, std::nullopt, default_priors());
  CHECK(plate_only.dim() == 3);
}

TEST_CASE("without wheel curves S is fixed and the bevameter fit is that of six parameters", "[bayes][wheel]") {
  Rng rng(32);
  const ParamVector t = truth();
  const SyntheticDesign design;
  const PlateData plate = synthesize_plate(t, design, rng);
  const ShearData shear = synthesize_shear(t, design, rng);
  const CalibrationProblem problem(plate, shear, default_priors());
  CHECK(problem.num_types() == 2);
  CHECK_FALSE(problem.has_wheel());
  CHECK(problem.dim() == 6);
  CHECK(problem.fixed_values()[kSlipSinkage] == 1.5);
  for (const auto& note : problem.notes()) CHECK(note.find("S ") == std::string::npos);  // S is not the user's concern
}

TEST_CASE("a slip-sinkage S fitted to wheel data is what the wheel needs: S = 0 misses the sinkage",
          "[bayes][wheel]") {
  // The same data seen through a problem with S fixed at 0 (no slip sinkage): its best fit leaves the
  // sinkage at slip 0.7 short by far more than the noise, so S carries information the other six do not.
  Rng rng(33);
  const ParamVector t = truth();
  const SyntheticDesign design;
  const PlateData plate = synthesize_plate(t, design, rng);
  const ShearData shear = synthesize_shear(t, design, rng);
  const WheelData wheel = synthesize_wheel(t, {0.1, 0.3, 0.5, 0.7}, {1059.48}, 0.0, rng);
  Priors priors = default_priors();
  priors[kSlipSinkage] = fixed_prior(0.0);
  const CalibrationProblem problem(plate, shear, priors, NoiseModel::kRelative, wheel);
  const PointEstimate est = estimate_point(problem, PointEstimateOptions{.seed = 5});
  const WheelPrediction& f = problem.predict_wheel(est.map);
  INFO("sinkage at slip 0.7: " << f.sinkage.back() << " m against " << wheel.points.back().sinkage << " m");
  CHECK(f.sinkage.back() < 0.7 * wheel.points.back().sinkage);
}

namespace {
// The annulus's data as a soil whose Mohr-Coulomb strength is the set's over R, with its own Janosi
// k: c / R and tan(phi) / R.
ParamVector annulus_view(const ParamVector& set, double R, double k_annulus) {
  ParamVector a = set;
  a[kCohesion] = set[kCohesion] / R;
  a[kFriction] = std::atan(std::tan(set[kFriction] * kPi / 180.0) / R) * 180.0 / kPi;
  a[kJanosi] = k_annulus;
  return a;
}
}  // namespace

TEST_CASE("with the annulus's law scaled, one wheel load and the annulus recover c, phi, k, R and k_annulus",
          "[bayes][wheel][annulus]") {
  // The annulus reads 1/1.6 of the wheel's strength and develops it over 6 mm instead of 25: the
  // annulus then gives c against tan(phi), the wheel (one load) the strength's level and k.
  Rng rng(35);
  const ParamVector t = truth();
  const double R = 1.6, k_annulus = 0.006;
  SyntheticDesign design;
  const PlateData plate = synthesize_plate(t, design, rng);
  const ShearData shear = synthesize_shear(annulus_view(t, R, k_annulus), design, rng);
  const WheelData wheel = synthesize_wheel(t, {0.1, 0.3, 0.5, 0.7}, {1059.48}, 0.02, rng);
  const CalibrationProblem scaled(plate, shear, default_priors(), NoiseModel::kRelative, wheel, AnnulusLaw::kScaled);
  REQUIRE(scaled.dim() == 9);
  CHECK(scaled.reported(kShearRatio));
  CHECK(scaled.reported(kAnnulusJanosi));

  const PointEstimate est = estimate_point(scaled, PointEstimateOptions{.seed = 5});
  const ParamVector& p = est.map;
  INFO("R " << p[kShearRatio] << ", k_annulus " << p[kAnnulusJanosi] << ", c " << p[kCohesion] << ", phi "
            << p[kFriction] << ", k " << p[kJanosi] << ", S " << p[kSlipSinkage] << "\n"
            << est.ceres_report);
  CHECK(rel(p[kShearRatio], R) < 0.05);
  CHECK(rel(p[kAnnulusJanosi], k_annulus) < 0.05);
  CHECK(rel(p[kCohesion], t[kCohesion]) < 0.1);
  CHECK(rel(p[kFriction], t[kFriction]) < 0.05);
  CHECK(rel(p[kJanosi], t[kJanosi]) < 0.1);
  CHECK(rel(p[kSlipSinkage], t[kSlipSinkage]) < 0.05);

  // The shared law must take one strength and one k from both: it misses the wheel's pull by far
  // more than the noise at some calibration slip.
  const CalibrationProblem shared(plate, shear, default_priors(), NoiseModel::kRelative, wheel);
  CHECK_FALSE(shared.reported(kShearRatio));
  REQUIRE(shared.dim() == 7);
  const PointEstimate one = estimate_point(shared, PointEstimateOptions{.seed = 5});
  const WheelPrediction& f = shared.predict_wheel(one.map);
  double worst = 0;
  for (std::size_t i = 0; i < wheel.points.size(); ++i)
    worst = std::max(worst, rel(f.dbp[i], wheel.points[i].dbp));
  INFO("shared law: worst pull error " << worst);
  CHECK(worst > 0.15);
}

TEST_CASE("the annulus's law scaled needs both shear and wheel curves", "[bayes][wheel][annulus]") {
  Rng rng(36);
  const ParamVector t = truth();
  const SyntheticDesign design;
  const PlateData plate = synthesize_plate(t, design, rng);
  const ShearData shear = synthesize_shear(t, design, rng);
  const WheelData wheel = synthesize_wheel(t, {0.1, 0.5}, {1059.48}, 0.02, rng);
  CHECK_THROWS_WITH(CalibrationProblem(plate, shear, default_priors(), NoiseModel::kRelative, std::nullopt,
                                       AnnulusLaw::kScaled),
                    Catch::Contains("--annulus-law scaled") && Catch::Contains("no wheel curves"));
  CHECK_THROWS_WITH(CalibrationProblem(plate, std::nullopt, default_priors(), NoiseModel::kRelative, wheel,
                                       AnnulusLaw::kScaled),
                    Catch::Contains("no shear curves"));
  // A prior for R in the shared law is not used, and says so.
  Priors priors = default_priors();
  priors[kShearRatio].user_given = true;
  const CalibrationProblem shared(plate, shear, priors, NoiseModel::kRelative, wheel);
  CHECK(shared.fixed_values()[kShearRatio] == 1.0);
  CHECK(std::any_of(shared.notes().begin(), shared.notes().end(),
                    [](const std::string& n) { return n.find("prior of R is not used") != std::string::npos; }));
}

TEST_CASE("a given elastic stiffness is the set's and the wheel's; the plates' own fit is kept beside it",
          "[bayes][wheel][elastic]") {
  // The wheel's soil rebounds 10x softer than the default Ke that plates without unloading leave:
  // given that Ke, the steady wheel at the truth reproduces the curves and the MAP recovers the soil;
  // left to the plates' default, the same parameters miss the wheel's sinkage.
  Rng rng(35);
  const ParamVector t = truth();
  SyntheticDesign design;
  const PlateData plate = synthesize_plate(t, design, rng);
  const ShearData shear = synthesize_shear(t, design, rng);
  const double ke = 4e6;
  const WheelData wheel = synthesize_wheel(t, {0.1, 0.3, 0.5, 0.7}, {1059.48, 1600}, 0.0, rng, ke);
  const CalibrationProblem given(plate, shear, default_priors(), NoiseModel::kRelative, wheel, AnnulusLaw::kShared, ke);
  const CalibrationProblem plates(plate, shear, default_priors(), NoiseModel::kRelative, wheel);
  REQUIRE(given.elastic_given());
  CHECK_FALSE(plates.elastic_given());
  CHECK(given.soil_of(t).elastic_stiffness == ke);
  CHECK(plates.soil_of(t).elastic_stiffness == kDefaultElasticStiffness);
  CHECK(given.elastic().ke == plates.elastic().ke);  // the plates' fit (here their default) is unchanged
  const WheelPrediction at_given = given.predict_wheel(t);
  const WheelPrediction at_plates = plates.predict_wheel(t);
  double worst_plates = 0;
  for (std::size_t i = 0; i < wheel.points.size(); ++i) {
    INFO("row " << i);
    CHECK(rel(at_given.sinkage[i], wheel.points[i].sinkage) < 1e-6);  // the problem's quadrature tolerance
    CHECK(rel(at_given.dbp[i], wheel.points[i].dbp) < 1e-6);
    worst_plates = std::max(worst_plates, rel(at_plates.sinkage[i], wheel.points[i].sinkage));
  }
  CHECK(worst_plates > 0.05);

  const PointEstimate est = estimate_point(given, PointEstimateOptions{.seed = 5});
  const ParamVector& p = est.map;
  INFO("S " << p[kSlipSinkage] << ", n " << p[kN] << ", phi " << p[kFriction] << ", k " << p[kJanosi]);
  CHECK(rel(p[kSlipSinkage], t[kSlipSinkage]) < 0.05);
  CHECK(rel(p[kFriction], t[kFriction]) < 0.05);
  CHECK(rel(p[kJanosi], t[kJanosi]) < 0.05);

  CHECK_THROWS_WITH(CalibrationProblem(plate, shear, default_priors(), NoiseModel::kRelative, wheel,
                                       AnnulusLaw::kShared, -1.0),
                    Catch::Contains("--elastic-stiffness") && Catch::Contains("-1"));
}
