#pragma once
// Vehicles and drivers the ROM tests share: the presets, and variants with the effects that a
// check needs isolated (no engine losses, one gear, chosen resistances).
#include <vector>

#include "core/vehicle/driver_inputs.hpp"
#include "rom/rom_run.hpp"
#include "rom/rom_vehicle_json.hpp"

namespace terracal::rom::testing {

inline RomVehicle hmmwv() { return load_rom_vehicle("hmmwv"); }

// The HMMWV coasting without engine losses, rolling resistance or drag: it keeps its speed.
inline RomVehicle frictionless_hmmwv() {
  RomVehicle v = hmmwv();
  v.powertrain.losses = Table1d{};
  v.effects &= ~(kEffectRollingResistance | kEffectAeroDrag | kEffectTorqueConverter);
  v.powertrain.crank_inertia = 1e-3;
  return v;
}

// Constant inputs from t = 0 on.
inline DriverSeries constant_inputs(double steering, double throttle, double braking) {
  return DriverSeries::from_rows({0.0, 1.0}, {steering, steering}, {throttle, throttle}, {braking, braking});
}

inline RomRunResult run(const RomVehicle& v, const DriverSeries& inputs, RomRunOptions o) {
  RomDriver d;
  d.series = &inputs;
  return run_rom(v, d, o);
}

inline RomRunOptions options(RomModel m, double end_time, double initial_speed) {
  RomRunOptions o;
  o.model = m;
  o.end_time = end_time;
  o.initial_speed = initial_speed;
  return o;
}

}  // namespace terracal::rom::testing
