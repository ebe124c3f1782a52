// The forward models against independent numerical integration (GSL QAG),
// across the series / closed-form switch, in both limits, and through the shared-kernel path.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>

#include <gsl/gsl_integration.h>

#include "bayes/calibration_problem.hpp"
#include "bayes/forward_models.hpp"
#include "bayes/synthetic_data.hpp"

using namespace terracal;
using namespace terracal::bayes;

namespace {

double integrate(const std::function<double(double)>& f, double a, double b) {
  gsl_integration_workspace* w = gsl_integration_workspace_alloc(1000);
  gsl_function F;
  F.function = [](double x, void* p) { return (*static_cast<const std::function<double(double)>*>(p))(x); };
  F.params = const_cast<std::function<double(double)>*>(&f);
  double result = 0, error = 0;
  gsl_integration_qag(&F, a, b, 0, 1e-13, 1000, GSL_INTEG_GAUSS61, w, &result, &error);
  gsl_integration_workspace_free(w);
  return result;
}

}  // namespace

TEST_CASE("shear development H(x) matches quadrature on both sides of the series switch", "[bayes][forward]") {
  for (double x : {1e-6, 1e-3, 0.1, 0.5, 0.999, 1.0, 1.001, 2.0, 5.0, 30.0, 300.0}) {
    const double expected = integrate([](double t) { return t * t * -std::expm1(-t); }, 0, x) / (x * x * x);
    INFO("x = " << x);
    CHECK(shear_development(x) == Approx(expected).epsilon(1e-12));
  }
  CHECK(shear_development(1e6) == Approx(1.0 / 3.0).epsilon(1e-12));
}

TEST_CASE("annulus torque is the integral of tau r dA over the annulus", "[bayes][forward]") {
  const double r_in = 0.15, r_out = 0.20, W = 700, c = 1300, phi = 31.1, k = 0.012;
  const double area = kPi * (r_out * r_out - r_in * r_in);
  const double tau_max = c + W / area * std::tan(phi * kPi / 180);
  for (double theta : {1e-4, 0.01, 0.05, 0.2, 1.0}) {
    const double expected =
        integrate([&](double r) { return tau_max * (1 - std::exp(-r * theta / k)) * r * 2 * kPi * r; }, r_in, r_out);
    INFO("theta = " << theta);
    CHECK(annulus_torque(r_in, r_out, W, theta, c, phi, k) == Approx(expected).epsilon(1e-12));
  }
  // theta -> infinity: the fully developed torque 2 pi tau_max (R^3 - r^3) / 3.
  CHECK(annulus_torque(r_in, r_out, W, 1e6, c, phi, k) ==
        Approx(annulus_torque_developed(r_in, r_out, W, c, phi)).epsilon(1e-12));
  CHECK(annulus_torque_developed(r_in, r_out, W, c, phi) ==
        Approx(2 * kPi * tau_max * (std::pow(r_out, 3) - std::pow(r_in, 3)) / 3));
}

TEST_CASE("plate force is pi r^2 (Kc/r + Kphi) z^n", "[bayes][forward]") {
  CHECK(plate_force(0.2, 0.05, 990.0, 1528430.0, 1.1) ==
        Approx(kPi * 0.04 * (990 / 0.2 + 1528430) * std::pow(0.05, 1.1)).epsilon(1e-14));
  CHECK(plate_force(0.2, 0.0, 990.0, 1528430.0, 1.1) == 0.0);
}

TEST_CASE("the shared-kernel predictions equal the row-by-row forward models", "[bayes][forward]") {
  const ParamVector truth = {102000, 5301000, 0.79, 1300, 31.1, 0.012};
  SyntheticDesign d;
  d.shear_pressures = {2e3, 9e3, 20e3};
  Rng rng(3);
  const PlateData plate = synthesize_plate(truth, d, rng);
  ShearData shear = synthesize_shear(truth, d, rng);
  shear.points.push_back({0.15, 0.2, 500.0, 42.0, 0.0, true, 0});  // a developed row
  const CalibrationProblem pb(plate, shear, default_priors());
  const ParamVector p = {5000, 2e6, 1.05, 800, 25, 0.02};
  const auto fp = pb.predict_all(0, p);
  REQUIRE(pb.set(0).kernels() == static_cast<std::size_t>(d.plate_points));  // sinkages shared by both plates
  for (std::size_t i = 0; i < fp.size(); ++i)
    CHECK(fp[i] ==
          Approx(plate_force(plate.points[i].radius, plate.points[i].sinkage, p[kKc], p[kKphi], p[kN])).epsilon(1e-14));
  const auto fs = pb.predict_all(1, p);
  REQUIRE(pb.set(1).kernels() ==
          static_cast<std::size_t>(d.shear_points) + 1);  // angles shared by the loads, + developed
  for (std::size_t i = 0; i < fs.size(); ++i) {
    const auto& q = shear.points[i];
    const double expected = q.developed ? annulus_torque_developed(q.inner_radius, q.outer_radius, q.normal_load,
                                                                   p[kCohesion], p[kFriction])
                                        : annulus_torque(q.inner_radius, q.outer_radius, q.normal_load, q.angle,
                                                         p[kCohesion], p[kFriction], p[kJanosi]);
    CHECK(fs[i] == Approx(expected).epsilon(1e-14));
  }
}
