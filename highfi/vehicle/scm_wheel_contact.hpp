#pragma once
// The full vehicle's wheels on SCM soil (lowfi::ScmWheels): each wheel a rigid cylinder about its
// spindle's y axis, centred on the spindle. Every soil step the vehicle's run hands over the spindles'
// present states (the run stops the integrator exactly there); over the next soil step the wrench on
// each spindle goes linearly from the previous step's soil wrench to this one's, so that it is
// continuous in time (a wrench that jumped every step would cost the integrator several steps of
// its own per soil step) at the price of a delay of one soil step.
#include <vector>

#include "highfi/multibody/force_elements.hpp"
#include "highfi/vehicle/rigid_ground_tire.hpp"
#include "lowfi/scm_wheels.hpp"

namespace terracal::vehicle {

class ScmWheelContact {
 public:
  ScmWheelContact(const lowfi::ScmSoil& soil, const lowfi::ScmSettings& settings, const lowfi::ScmWheelShape& wheel,
                  std::size_t wheels);
  // One soil step at the spindles' present states (bodies[spindles[k]] carries wheel k).
  void step(double t, const std::vector<mb::RigidBody>& bodies, const std::vector<int>& spindles);
  // The soil's wrench on wheel k at time t, added to its spindle's: force (world), torque about the
  // centre (the spindle's frame).
  void apply(std::size_t k, double t, const mb::RigidBody& spindle, mb::Wrench& w) const;
  // Wheel k's contact for wheels.csv: the held forces along the wheel's heading, to its left and up,
  // the slips (longitudinal (w R - v_x) / max(|w R|, |v_x|), lateral -v_y / |v_x|, both 0 below
  // 1 mm/s), and the sinkage: how far the lowest point of the wheel's centre plane lies below the
  // undisturbed surface.
  TireContact contact(std::size_t k, const mb::RigidBody& spindle) const;
  double time_step() const { return soil_.time_step(); }
  double time() const { return soil_.time(); }
  const lowfi::ScmWheels& soil() const { return soil_; }

 private:
  lowfi::ScmWheels soil_;
  double radius_ = 0;
  double stepped_at_ = 0;                      // the time of the last soil step
  std::vector<BodyWrench> previous_, latest_;  // the soil wrenches of the last two steps
};

}  // namespace terracal::vehicle
