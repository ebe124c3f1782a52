#pragma once
// Powertrain pieces shared by the reduced-order vehicles and the full vehicle: an engine torque map
// with losses, a torque converter (capacity-factor and torque-ratio maps, as Chrono's
// ChShaftsTorqueConverter), an automatic gearbox that shifts at engine speeds, open differentials
// and brakes. All SI: speeds in rad/s, torques in N m. Plain structs, host and device.
#include <cmath>

#include "core/host_device.hpp"
#include "core/vehicle/table_1d.hpp"

namespace terracal {

enum class Drive : int { kAll = 0, kRear = 1, kFront = 2 };

struct PowertrainParams {
  static constexpr int kMaxGears = 10;
  Table1d max_torque;        // full-throttle engine torque [N m] against crank speed [rad/s]
  Table1d losses;            // torque the engine always adds (friction, pumping; negative) [N m]
  double crank_inertia = 0;  // [kg m^2]
  Table1d capacity_factor;   // K(speed ratio) [rad/s / sqrt(N m)]: pump torque = (omega_pump / K)^2
  Table1d torque_ratio;      // turbine torque / pump torque against speed ratio
  int gears = 0;
  double gear_ratio[kMaxGears] = {};       // wheel speed / turbine speed (final drive included)
  double upshift_speed[kMaxGears] = {};    // crank speed above which the next gear is taken [rad/s]
  double downshift_speed[kMaxGears] = {};  // crank speed below which the previous gear is taken
  double max_brake_torque = 0;             // per wheel at braking = 1 [N m]
  Drive drive = Drive::kAll;
};

// Engine torque at the crank: throttle times the full-load curve, plus the losses.
TERRACAL_HD_INLINE double engine_torque(const PowertrainParams& p, double crank_speed, double throttle) {
  return throttle * p.max_torque(crank_speed) + p.losses(crank_speed);
}

// Torque-converter torques with the pump on the crank and the turbine on the gearbox input.
// Below a speed ratio of 1 the pump absorbs (omega_pump / K)^2 and the turbine delivers TR times
// that; above 1 (the wheels drive the engine) the roles swap, with K and TR taken at ratio 1. Maps
// end at K(1) finite, which would make the torque jump from +T to -T at ratio 1 (an ODE solver
// stalls there): within kConverterCouplingBand of 1 the torque fades linearly to zero instead.
inline constexpr double kConverterCouplingBand = 0.02;
struct ConverterTorques {
  double pump = 0;     // torque the converter takes from the crank [N m]
  double turbine = 0;  // torque it delivers to the gearbox input [N m]
};
TERRACAL_HD_INLINE ConverterTorques torque_converter(const PowertrainParams& p, double pump_speed,
                                                     double turbine_speed) {
  ConverterTorques t;
  const double wp = fabs(pump_speed), wt = fabs(turbine_speed);
  if (wp <= 0.0 && wt <= 0.0) return t;
  if (wt <= wp) {
    const double ratio = wt / wp;
    const double k = p.capacity_factor(ratio);
    const double fade = min_of(1.0, (1.0 - ratio) / kConverterCouplingBand);
    t.pump = fade * copysign((wp / k) * (wp / k), pump_speed);
    t.turbine = p.torque_ratio(ratio) * t.pump;
  } else {
    const double ratio = wp / wt;
    const double k = p.capacity_factor(1.0);
    const double fade = min_of(1.0, (1.0 - ratio) / kConverterCouplingBand);
    t.turbine = -fade * copysign((wt / k) * (wt / k), turbine_speed);
    t.pump = t.turbine;
  }
  return t;
}

// The automatic gearbox: one gear up above the gear's upshift speed, one down below its downshift
// speed, measured at the gearbox input (the turbine; the crank when there is no converter), as
// Chrono's automatic transmission does: a converter slipping at stall does not shift through every
// gear at once. Called between steps (the gear is a discrete state, not part of the ODE).
TERRACAL_HD_INLINE int shift_gear(const PowertrainParams& p, int gear, double input_speed) {
  if (gear + 1 < p.gears && input_speed > p.upshift_speed[gear]) return gear + 1;
  if (gear > 0 && input_speed < p.downshift_speed[gear]) return gear - 1;
  return gear;
}

// The gear a vehicle already rolling starts in, from its driven wheels' mean spin: the lowest whose
// gearbox input (spin / ratio) is below that gear's upshift speed, as if it had shifted up on the way.
// Shared by the reduced-order and the full vehicles, so that both start a manoeuvre at speed alike.
TERRACAL_HD_INLINE int starting_gear(const PowertrainParams& p, double wheel_spin) {
  int gear = 0;
  while (gear + 1 < p.gears && wheel_spin / p.gear_ratio[gear] > p.upshift_speed[gear]) ++gear;
  return gear;
}

// Which wheels the open differentials drive (FL, FR, RL, RR order for four wheels; front, rear axle
// for two).
TERRACAL_HD_INLINE bool is_driven(Drive d, bool front) {
  return d == Drive::kAll || (front ? d == Drive::kFront : d == Drive::kRear);
}

// Brake and rolling-resistance torques act against the spin like dry friction: a bound on the
// torque's magnitude. The fixed-step scheme applies them implicitly (they stop a wheel, never
// reverse it); an ODE solver uses this smooth sign, whose width is the spin speed below which the
// torque fades.
inline constexpr double kDryFrictionSpinWidth = 0.05;  // [rad/s]
TERRACAL_HD_INLINE double dry_friction_torque(double bound, double omega) {
  return -bound * omega / sqrt(omega * omega + kDryFrictionSpinWidth * kDryFrictionSpinWidth);
}

}  // namespace terracal
