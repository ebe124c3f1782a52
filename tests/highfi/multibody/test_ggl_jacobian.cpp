// The integrator's sparse Newton matrix against differences of the whole residual.
#include <catch2/catch.hpp>

#include "highfi/multibody/mb_integrator.hpp"
#include "tests/highfi/multibody/ggl_jacobian_check.hpp"
#include "tests/highfi/multibody/mb_test_systems.hpp"

using namespace terracal;

TEST_CASE("multibody: the sparse Newton matrix equals the residual's differences (four-bar with a spring)",
          "[multibody]") {
  mb::MbSystem s;
  test::four_bar(s);
  // A spring-damper between the coupler and the rocker: a force element whose q- and u-derivatives
  // the matrix differences by colour.
  mb::SpringDamper spring;
  spring.name = "spring";
  spring.i = 2, spring.j = 3;
  spring.si = mb::Vec3(0.1, 0, 0), spring.sj = mb::Vec3(-0.05, 0, 0);
  spring.rest_length = 0.2;
  spring.law = mb::linear_law(2e3, 50);
  s.springs.push_back(spring);
  s.assemble();
  const test::JacobianError e = test::ggl_jacobian_error(s, 0.0, 2.0, 50.0);
  INFO("largest error relative to its row's largest entry: " << e.error << " at row " << e.row << ", column "
                                                             << e.column << " (" << e.ours << " against " << e.reference
                                                             << ")");
  CHECK(e.error < 1e-5);
}

TEST_CASE("multibody: the sparse and the dense Newton matrices integrate the four-bar alike", "[multibody]") {
  // The same residual, so the same solution within the tolerance; the same Newton convergence (a
  // wrong matrix shows as more convergence failures and Jacobian evaluations).
  std::vector<double> angle;
  std::vector<mb::MbIntegratorStats> stats;
  for (auto kind : {mb::MbIntegratorOptions::Jacobian::sparse, mb::MbIntegratorOptions::Jacobian::dense_difference}) {
    mb::MbSystem s;
    const int crank = test::four_bar(s);
    mb::MbIntegratorOptions o{1e-8, 1e-10};
    o.jacobian = kind;
    mb::MbIntegrator in(s, o);
    in.advance(5.0);
    CHECK(in.constraint_violation() < 1e-8);
    const mb::Quat q = s.bodies[std::size_t(crank)].orientation;
    angle.push_back(std::atan2(q.y(), q.w()));
    stats.push_back(in.stats());
  }
  INFO("steps " << stats[0].steps << " and " << stats[1].steps << ", Newton failures " << stats[0].newton_failures
                << " and " << stats[1].newton_failures << ", Jacobians " << stats[0].jacobians << " and "
                << stats[1].jacobians);
  CHECK(std::abs(angle[0] - angle[1]) < 1e-4);
  CHECK(stats[0].newton_failures <= stats[1].newton_failures + 2);
  CHECK(stats[0].jacobians <= 1.2 * double(stats[1].jacobians));
  CHECK(std::abs(double(stats[0].steps - stats[1].steps)) <= 0.1 * double(stats[1].steps));
}
