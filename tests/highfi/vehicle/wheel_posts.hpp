#pragma once
// The steering tests' stand: the chassis held in the air and a stiff post under each wheel centre that
// holds it at its design height (within ~1e-4 m), so that the dynamic steering can be compared with the
// kinematic solve at zero travel.
#include "highfi/vehicle/full_vehicle.hpp"

namespace terracal::test {

inline void hold_on_posts(vehicle::FullVehicle& v) {
  mb::MbSystem& s = v.system();
  s.bodies[std::size_t(v.chassis())].fixed = true;
  s.index();
  for (const auto& w : v.corners()) {
    const int spindle = w.spindle;
    const double design = s.bodies[std::size_t(spindle)].position.z();
    s.external.push_back({[=](double, const std::vector<mb::RigidBody>& b, std::vector<mb::Wrench>& f) {
                            const mb::RigidBody& sp = b[std::size_t(spindle)];
                            f[std::size_t(spindle)].force.z() +=
                                2e7 * (design - sp.position.z()) - 2e4 * sp.velocity.z();
                          },
                          {spindle}});
  }
}

}  // namespace terracal::test
