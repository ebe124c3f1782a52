// The analytic Wong-Reece rigid wheel (Wong & Reece 1967; Wong, Theory of Ground Vehicles, ch. 5):
// load equilibrium, Bekker's closed-form compaction resistance, slip/load trends, and bad input.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <gsl/gsl_integration.h>

#include "core/errors.hpp"
#include "lowfi/wong_reece.hpp"

using namespace terracal;
using namespace terracal::lowfi;
using Catch::Matchers::Contains;

namespace {

ScmSoil dry_sand() { return reference_dry_sand(); }

const WongReeceWheel kWheel{0.47, 0.25};
const double kLoad = 108 * 9.81;  // the default wheel (docs/formats.md, "Wheel"): 108 kg on Earth

// Test-side quadrature (GSL QAGS), independent of the model's own integration code.
double integrate(double (*f)(double, void*), void* params, double a, double b) {
  gsl_integration_workspace* w = gsl_integration_workspace_alloc(1000);
  gsl_function F{f, params};
  double result = 0, error = 0;
  gsl_integration_qags(&F, a, b, 0, 1e-12, 1000, w, &result, &error);
  gsl_integration_workspace_free(w);
  return result;
}

}  // namespace

TEST_CASE("Wong-Reece: the entry angle balances the load", "[lowfi][wong_reece]") {
  const ScmSoil soil = dry_sand();
  const WongReeceOptions options;
  for (double load : {150.0, kLoad, 3000.0, 8000.0}) {
    for (double slip : {-0.5, -0.1, 0.0, 0.1, 0.5, 0.9}) {
      INFO("load " << load << " N, slip " << slip);
      const WongReeceResult r = wong_reece(soil, kWheel, load, slip);
      CHECK(r.load == load);
      CHECK(r.slip == slip);
      CHECK(r.vertical_force == Approx(load).epsilon(1e-6));
      CHECK(r.entry_angle > 0);
      CHECK(r.entry_angle <= M_PI / 2);
      CHECK(r.sinkage == Approx(kWheel.radius * (1 - std::cos(r.entry_angle))).epsilon(1e-12));
      CHECK(r.max_stress_angle == Approx((options.c1 + options.c2 * slip) * r.entry_angle).epsilon(1e-12));
    }
  }
}

namespace {

struct FrontOnly {
  double k_bekker, theta1, n;  // sigma = k_bekker (cos θ − cos θ1)^n, k_bekker = (Kc/b + Kphi) r^n
};
double sigma_cos(double theta, void* p) {
  const auto* f = static_cast<const FrontOnly*>(p);
  return f->k_bekker * std::pow(std::max(0.0, std::cos(theta) - std::cos(f->theta1)), f->n) * std::cos(theta);
}

}  // namespace

// With θm = 0 the Bekker law (cos θ − cos θ1)^n covers the whole contact, and on a soil without
// strength (c = 0, φ = 0, so τ = 0) the drawbar pull is Bekker's compaction resistance
// −b (Kc/b + Kφ) z^(n+1) / (n+1) exactly (substitute u = cos θ − cos θ1 in r b ∫ σ sin θ dθ).
// θm = 0 needs c1 = c2 = 0; the brief's c1 = 1 would give θm = θ1, where the rear law maps every
// angle to θ1 and σ ≡ 0: that case is checked below to carry nothing.
TEST_CASE("Wong-Reece: Bekker's compaction resistance in closed form", "[lowfi][wong_reece]") {
  ScmSoil soil = dry_sand();
  soil.cohesion = 0;
  soil.friction_deg = 0;
  WongReeceOptions options;
  options.c1 = 0;
  options.c2 = 0;
  const double r = kWheel.radius, b = kWheel.width;
  for (double n : {0.5, 1.0, 1.1, 1.6}) {
    soil.n = n;
    for (double slip : {0.0, 0.3}) {
      INFO("n " << n << ", slip " << slip);
      const WongReeceResult res = wong_reece(soil, kWheel, kLoad, slip, options);
      const double k_sum = soil.Kc / b + soil.Kphi;
      CHECK(res.max_stress_angle == 0);
      CHECK(res.dbp == Approx(-b * k_sum * std::pow(res.sinkage, n + 1) / (n + 1)).epsilon(1e-6));
      CHECK(res.torque == 0);
      // load = r b ∫ σ cos θ dθ, by the test's own quadrature, and in closed form for n = 1:
      // ∫ (cos θ − cos θ1) cos θ dθ = θ1/2 − sin(2 θ1)/4.
      FrontOnly f{k_sum * std::pow(r, n), res.entry_angle, n};
      CHECK(r * b * integrate(&sigma_cos, &f, 0, res.entry_angle) == Approx(kLoad).epsilon(1e-6));
      if (n == 1.0) {
        const double t1 = res.entry_angle;
        CHECK(r * r * b * k_sum * (t1 / 2 - std::sin(2 * t1) / 4) == Approx(kLoad).epsilon(1e-6));
      }
    }
  }
  options.c1 = 1;  // θm = θ1: σ ≡ 0 and τ ≡ 0, so nothing carries the wheel
  CHECK_THROWS_AS(wong_reece(soil, kWheel, kLoad, 0.3, options), RunError);
}

TEST_CASE("Wong-Reece: trends with slip and load on dry sand", "[lowfi][wong_reece]") {
  const ScmSoil soil = dry_sand();
  std::vector<WongReeceResult> runs;
  const std::vector<double> slips{0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8};
  for (double s : slips) runs.push_back(wong_reece(soil, kWheel, kLoad, s));
  for (std::size_t i = 1; i < runs.size(); ++i) {
    INFO("slip " << slips[i - 1] << " -> " << slips[i]);
    CHECK(runs[i].torque > runs[i - 1].torque);
    // Slip sinkage: θm = (c1 + c2 s) θ1 moves forward with slip, the rear carries less, the wheel sinks.
    CHECK(runs[i].sinkage > runs[i - 1].sinkage);
    // DBP rises while the shear develops, then flattens: past s ≈ 0.7 the growing compaction
    // resistance of the slip sinkage wins (235.4 N at 0.7, 231.6 N at 0.8), as in Wong-Reece's model.
    if (slips[i] <= 0.6)
      CHECK(runs[i].dbp > runs[i - 1].dbp);
    else
      CHECK(runs[i].dbp == Approx(runs[i - 1].dbp).epsilon(0.02));
  }
  CHECK(runs[5].slip == 0.5);
  CHECK(runs[5].dbp > 0);
  CHECK(runs[0].dbp < 0.25 * runs[5].dbp);  // little traction at small slip: shear barely developed

  // Skid brakes the wheel: the shear reverses, the torque is negative and the pull drops.
  const WongReeceResult free_rolling = wong_reece(soil, kWheel, kLoad, 0.0);
  const WongReeceResult skid = wong_reece(soil, kWheel, kLoad, -0.3);
  CHECK(free_rolling.dbp < 0);  // compaction resistance with almost no shear
  CHECK(skid.torque < 0);
  CHECK(skid.dbp < free_rolling.dbp);

  double previous = 0;
  for (double load : {250.0, 500.0, 1000.0, 2000.0, 4000.0}) {
    const double z = wong_reece(soil, kWheel, load, 0.2).sinkage;
    INFO("load " << load << " N");
    CHECK(z > previous);
    previous = z;
  }
}

TEST_CASE("Wong-Reece: bad input and an overloaded wheel", "[lowfi][wong_reece]") {
  const ScmSoil soil = dry_sand();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(wong_reece(soil, kWheel, kLoad, 1.0), InputError);
  CHECK_THROWS_WITH(wong_reece(soil, kWheel, kLoad, 1.0), Contains("slip = 1") && Contains("-1 < slip < 1"));
  CHECK_THROWS_AS(wong_reece(soil, kWheel, kLoad, -1.0), InputError);
  CHECK_THROWS_AS(wong_reece(soil, kWheel, kLoad, nan), InputError);
  CHECK_THROWS_WITH(wong_reece(soil, kWheel, -1.0, 0.2), Contains("load = -1") && Contains("> 0 N"));
  CHECK_THROWS_AS(wong_reece(soil, kWheel, 0.0, 0.2), InputError);
  CHECK_THROWS_AS(wong_reece(soil, kWheel, std::numeric_limits<double>::infinity(), 0.2), InputError);
  CHECK_THROWS_WITH(wong_reece(soil, WongReeceWheel{0.0, 0.25}, kLoad, 0.2), Contains("wheel radius = 0"));
  CHECK_THROWS_WITH(wong_reece(soil, WongReeceWheel{0.47, -0.25}, kLoad, 0.2), Contains("wheel width = -0.25"));
  ScmSoil no_k = soil;
  no_k.janosi_k = 0;
  CHECK_THROWS_WITH(wong_reece(no_k, kWheel, kLoad, 0.2), Contains("janosi_k"));
  WongReeceOptions bad_tol;
  bad_tol.rel_tol = 0;
  CHECK_THROWS_WITH(wong_reece(soil, kWheel, kLoad, 0.2, bad_tol), Contains("rel_tol"));

  // At θ1 = π/2 this wheel on dry sand carries about 41 kN; 1 MN would bury the axle.
  CHECK_THROWS_AS(wong_reece(soil, kWheel, 1e6, 0.2), RunError);
  CHECK_THROWS_WITH(wong_reece(soil, kWheel, 1e6, 0.2), Contains("axle"));
}
