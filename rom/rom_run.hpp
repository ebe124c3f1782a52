#pragma once
// One reduced-order vehicle on the CPU: a model (11/18 DOF), an integrator (CVODES BDF with user
// tolerances, or the fixed-step half-implicit scheme the GPU batch uses) and a driver (a driver file
// or a built-in manoeuvre), sampled at a fixed output rate. The integrators know nothing of the
// physics: they see a model's right-hand side (the SUNDIALS pattern).
#include <string>
#include <utility>
#include <vector>

#include "core/vehicle/driver_inputs.hpp"
#include "core/vehicle/maneuver.hpp"
#include "rom/rom_sample.hpp"
#include "rom/rom_vehicle.hpp"

namespace terracal::rom {

enum class RomModel { k11Dof, k18Dof, k24Dof };
enum class RomIntegrator { kCvodes, kHalfImplicit };

const char* model_name(RomModel m);
const char* integrator_name(RomIntegrator i);
// Refuses (InputError) a vehicle naming an effect that model cannot simulate.
void check_model_effects(const RomVehicle& v, RomModel m);

struct RomRunOptions {
  RomModel model = RomModel::k18Dof;
  RomIntegrator integrator = RomIntegrator::kHalfImplicit;
  double step = 1e-3;          // fixed step of the half-implicit scheme [s]
  double rtol = 1e-6;          // CVODES relative tolerance
  double atol = 1e-8;          // CVODES absolute tolerance (every state)
  double end_time = 10.0;      // [s]
  double initial_speed = 0.0;  // straight ahead [m/s]; negative rolls backwards
  double output_rate = 100.0;  // samples per second [Hz]
};

// Where the inputs come from: a driver series (a function of time: CVODES evaluates it within its
// steps) or a manoeuvre with controllers (evaluated once per control period, held in between).
struct RomDriver {
  const DriverSeries* series = nullptr;
  Maneuver* maneuver = nullptr;
  double control_period = 0.01;  // [s]
};

struct RomRunResult {
  std::vector<RomSample> samples;
  // A manoeuvre's inputs: each control time and the inputs held from it until the next (empty with a
  // driver series).
  std::vector<std::pair<double, DriverInput>> held_inputs;
  long steps = 0;            // integrator steps
  long rhs_evaluations = 0;  // right-hand-side evaluations
  double wall_seconds = 0;
};

// Throws RunError when the run fails: a fixed step too large (the state diverged: the message gives
// the time and says to shrink --step), or CVODES failing.
RomRunResult run_rom(const RomVehicle& vehicle, RomDriver& driver, const RomRunOptions& options);

}  // namespace terracal::rom
