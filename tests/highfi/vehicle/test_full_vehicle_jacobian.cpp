// The integrator's sparse Newton matrix for the whole HMMWV (joints, springs and shocks, tires,
// steering servo, driveline shafts, engine and torque converter) against differences of the residual.
#include <catch2/catch.hpp>

#include "highfi/vehicle/full_vehicle.hpp"
#include "tests/highfi/multibody/ggl_jacobian_check.hpp"

using namespace terracal;
using namespace terracal::vehicle;

TEST_CASE("full vehicle: the HMMWV's sparse Newton matrix equals the residual's differences", "[vehicle]") {
  const FullVehicleSpec spec = load_full_vehicle("hmmwv");
  FullVehicle v(spec, mb::Vec3(0, 0, spec.tire.unloaded_radius - 0.02));  // tires pressed into the ground
  v.set_driver([](double) { return DriverInput{0.2, 0.5, 0.0}; });
  mb::MbSystem& s = v.system();
  s.assemble();
  // The forces of the 19 bodies and 10 shafts are differenced in a few groups: the tires, brakes and
  // steering servo name the bodies they act on.
  CHECK(mb::GglJacobian(s).colors() <= 8);
  const test::JacobianError e = test::ggl_jacobian_error(s, 0.5, 0.5, 1e3);
  INFO("largest error relative to its row's largest entry: " << e.error << " at row " << e.row << ", column "
                                                             << e.column << " (" << e.ours << " against " << e.reference
                                                             << ")");
  CHECK(e.error < 1e-5);
}
