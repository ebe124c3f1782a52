#pragma once
// The fixed-step half-implicit scheme (LFDM's, a semi-implicit Euler step): velocities and the other
// first-order states from the right-hand side at the start of the step, brake and rolling resistance
// applied implicitly to the new spins (they stop a wheel within the step, never reverse it), then
// the positions from the new velocities; the gear is shifted after the step. Host and device: the
// CPU batch, the single-vehicle run and the GPU batch all step through this function.
#include <cmath>

#include "core/host_device.hpp"
#include "core/vehicle/driver_inputs.hpp"
#include "core/vehicle/powertrain.hpp"
#include "rom/rom_vehicle.hpp"
#include "rom/wheel_group.hpp"

namespace terracal::rom {

// A state beyond these is a step too large for the scheme (it diverged), never a vehicle.
inline constexpr double kMaxSpeed = 1000.0;  // [m/s]
inline constexpr double kMaxSpin = 20000.0;  // wheel or crank [rad/s]

// Nothing to do at the start of a step.
struct NoStartHook {
  TERRACAL_HD void operator()(const double*, const RomAux&) const {}
};

// `g`: the lanes that share the vehicle's wheels (rom/wheel_group.hpp); each ends with the same state.
// `at_start(y, aux)` sees the state at the start of the step with the right-hand side's aux there
// (accelerations, loads) before the step changes it: a sample taken at that time needs no right-hand
// side of its own.
template <class M, class G = OneLanePerVehicle, class AtStart = NoStartHook>
TERRACAL_HD bool half_implicit_step(const RomVehicle& v, const DriverInput& in, int& gear, double* y, double h,
                                    RomAux* aux, const G& g = G{}, const AtStart& at_start = AtStart{}) {
  double dy[M::kStates];
  M::rhs(v, in, gear, y, dy, aux, false, false, g);
  at_start(y, *aux);
  for (int i = 0; i < M::kStates; ++i)
    if (!M::is_position(i)) y[i] += h * dy[i];
  for (int w = 0; w < M::kWheels; ++w) {
    double& spin = y[M::kSpin + w];
    const double stop = h * aux->dry_torque[w] / aux->spin_inertia[w];
    spin = fabs(spin) <= stop ? 0.0 : spin - copysign(stop, spin);
  }
  M::kinematics(v, y, dy);
  for (int i = 0; i < M::kStates; ++i)
    if (M::is_position(i)) y[i] += h * dy[i];
  gear = shift_gear(v.powertrain, gear, aux->gearbox_input_speed);
  bool ok = fabs(y[M::kVx]) < kMaxSpeed && fabs(y[M::kVy]) < kMaxSpeed && fabs(y[M::kCrank]) < kMaxSpin;
  for (int w = 0; w < M::kWheels; ++w) ok = ok && fabs(y[M::kSpin + w]) < kMaxSpin;
  for (int i = 0; i < M::kStates; ++i) ok = ok && fabs(y[i]) <= 1.7e308;  // false for NaN and infinity
  return ok;
}

}  // namespace terracal::rom
