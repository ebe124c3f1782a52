#pragma once
// Engine to wheels for the reduced-order models: with the `torque_converter` effect the crank speed
// is a state behind the converter; without it the crank is geared rigidly to the mean speed of the
// driven wheels (open differentials), and its inertia couples those wheels.
#include "core/host_device.hpp"
#include "core/vehicle/powertrain.hpp"
#include "rom/rom_vehicle.hpp"

namespace terracal::rom {

struct Driveline {
  double wheel_torque = 0;  // drive torque on each driven wheel [N m]
  double crank_accel = 0;   // d(crank speed)/dt with the converter [rad/s^2]
  double engine_speed = 0;  // [rad/s]
  double input_speed = 0;   // gearbox input (turbine) [rad/s]
  double coupling = 0;      // locked crank: its inertia seen by each driven wheel pair, Jc / (n g)^2
};

TERRACAL_HD_INLINE Driveline driveline(const RomVehicle& v, int gear, double throttle, double crank_speed,
                                       double mean_driven_spin, int driven) {
  const PowertrainParams& p = v.powertrain;
  const double g = p.gear_ratio[gear];
  Driveline d;
  d.input_speed = mean_driven_spin / g;
  if (v.has(kEffectTorqueConverter)) {
    d.engine_speed = crank_speed;
    const ConverterTorques tc = torque_converter(p, crank_speed, mean_driven_spin / g);
    d.crank_accel = (engine_torque(p, crank_speed, throttle) - tc.pump) / p.crank_inertia;
    d.wheel_torque = tc.turbine / g / driven;
  } else {
    d.engine_speed = mean_driven_spin / g;
    d.wheel_torque = engine_torque(p, d.engine_speed, throttle) / g / driven;
    d.coupling = p.crank_inertia / ((driven * g) * (driven * g));
  }
  return d;
}

// Spin accelerations of n wheels with inertias j under torques tau, the driven ones coupled through
// the locked crank: j_i w_i' + c S = tau_i with S the driven wheels' summed acceleration, so
// S = sum(tau_i / j_i) / (1 + c sum(1 / j_i)) over the driven wheels.
TERRACAL_HD_INLINE void spin_accelerations(int n, const bool* driven, const double* j, double coupling,
                                           const double* tau, double* accel) {
  double num = 0, den = 1;
  for (int i = 0; i < n; ++i)
    if (driven[i]) num += tau[i] / j[i], den += coupling / j[i];
  const double s = num / den;
  for (int i = 0; i < n; ++i) accel[i] = (tau[i] - (driven[i] ? coupling * s : 0.0)) / j[i];
}

// The gear a vehicle rolling with the driven wheels' mean spin starts in (the lowest whose crank
// speed is below its upshift speed), and the crank speed that goes with it.
TERRACAL_HD_INLINE int initial_gear(const RomVehicle& v, double mean_spin, double* crank) {
  const int gear = starting_gear(v.powertrain, mean_spin);
  *crank = mean_spin / v.powertrain.gear_ratio[gear];
  return gear;
}

}  // namespace terracal::rom
