#pragma once
// One run of the full vehicle on rigid ground or SCM soil, driven by a driver file or a manoeuvre: the vehicle
// settles at rest first (not recorded: its springs lift it from the design position to its ride
// height), then starts at the initial speed; rows of trajectory.csv (as the reduced-order vehicles
// write them) and of wheels.csv at the output rate; with a snapshot folder, ParaView snapshots of the
// bodies (vehicle_vtu.hpp) at the snapshot rate and the collection listing them.
#include <optional>
#include <string>
#include <vector>

#include "core/vehicle/driver_inputs.hpp"
#include "core/vehicle/maneuver.hpp"
#include "highfi/vehicle/full_vehicle.hpp"

namespace terracal::vehicle {

struct VehicleRunOptions {
  double end_time = 10;          // s
  double initial_speed = 0;      // m/s, forward
  double output_rate = 100;      // rows per second
  double rtol = 1e-5;            // IDAS relative tolerance (absolute: rtol / 100)
  double max_step = 0;           // s, IDAS's largest step; 0: free
  double control_period = 0.01;  // s, a manoeuvre's controller period (each output reached linearly over it)
  double settle_time = 3;        // s at rest before the run (on SCM: on rigid ground, then as long on the soil)
  double friction = 1;           // the ground's friction over the tire data's
  // SCM soil instead of rigid ground: the wheels as rigid cylinders in it (scm_wheel_contact.hpp),
  // the soil stepped every scm.time_step from the time the vehicle is set down on it.
  std::optional<lowfi::ScmSoil> soil;
  lowfi::ScmSettings scm;
  // Snapshots: DIR/vehicle_NNNNN.vtu at times k / vtu_rate from 0 to end_time and DIR/vehicle.pvd;
  // "": none. One between two output rows is the integrator's interpolated state: its steps are the
  // same as without snapshots, except when it is the first output after a restart (the start, a gear
  // shift), where IDAS sizes its first step by the time asked for.
  std::string vtu_dir;
  double vtu_rate = 20;  // snapshots per second, in kVehicleVtuRate
};

// One row of trajectory.csv: the chassis (sprung mass) in the ground frame; vx, vy, ax, ay in the
// chassis frame.
struct VehicleSample {
  double time = 0, x = 0, y = 0, z = 0, yaw = 0, roll = 0, pitch = 0;
  double vx = 0, vy = 0, yaw_rate = 0, roll_rate = 0, ax = 0, ay = 0, engine_speed_rpm = 0;
  int gear = 0;  // 1-based
};

struct WheelSample {
  double time = 0;
  int wheel = 0;  // front left, front right, rear left, rear right (per axle, left first)
  TireContact contact;
};

// The driver inputs in effect at `time` (the trajectory's clock: 0 is trajectory.csv's first row).
struct DriverKnot {
  double time = 0;
  DriverInput input;
};

struct VehicleRunResult {
  std::vector<VehicleSample> samples;
  // The driver inputs applied, as knots that are linear between them (DriverSeries::at reproduces
  // them): a driver file's own rows; a manoeuvre's inputs at every control time (each ramp's start)
  // and at end_time. Times strictly increasing.
  std::vector<DriverKnot> inputs;
  std::vector<WheelSample> wheels;
  long steps = 0, residuals = 0;
  double wall_seconds = 0, max_constraint_violation = 0;
  long vtu_snapshots = 0;
  std::vector<std::string> vtu_bodies;  // with snapshots: the names that their cell array `body` indexes
};

// Every body moving forward (+x) at `speed`, wheels rolling at speed / unloaded radius, the gearbox in
// the gear the speed calls for (starting_gear) and the driveline's shafts turning with the wheels (then
// restart the integrator from this state).
void set_forward_speed(FullVehicle& v, double speed);

// Exactly one of series and maneuver is non-null.
VehicleRunResult run_full_vehicle(const FullVehicleSpec& spec, const DriverSeries* series, Maneuver* maneuver,
                                  const VehicleRunOptions& o);

}  // namespace terracal::vehicle
