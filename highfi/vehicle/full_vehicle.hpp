#pragma once
// The full vehicle: a rigid chassis, an axle of double-wishbone suspensions per axle entry, a wheel (and
// tire mass) on each spindle, and TMeasy tires on rigid flat ground, as one multibody system. Read
// from JSON (docs/formats.md, "Full vehicle") or the built-in HMMWV preset. The chassis frame is x
// forward, y left, z up; its origin is the reference point the suspension locations are given from.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "highfi/vehicle/double_wishbone.hpp"
#include "highfi/vehicle/driveline.hpp"
#include "highfi/vehicle/pitman_arm.hpp"
#include "highfi/vehicle/rack_pinion.hpp"
#include "highfi/vehicle/rigid_ground_tire.hpp"
#include "highfi/vehicle/scm_wheel_contact.hpp"

namespace terracal::vehicle {

struct AxleSpec {
  Vec3 location = Vec3::Zero();  // the suspension's origin in the chassis frame, m
  DoubleWishboneSpec suspension;
  bool steered = false;  // its tie rods end on the steering link (else on the chassis)
};

struct FullVehicleSpec {
  std::string name = "vehicle";
  BodySpec chassis;  // com in the chassis frame
  std::vector<AxleSpec> axles;
  bool has_steering = false;
  bool rack_steering = false;  // the steering's template: rack-and-pinion (else Pitman arm)
  PitmanArmSpec steering;
  RackPinionSpec rack;
  bool has_powertrain = false;
  PowertrainParams powertrain;
  DrivelineSpec driveline;
  double wheel_mass = 0;              // wheel and tire, kg
  Vec3 wheel_inertia = Vec3::Zero();  // about the wheel's centre, spin about y, kg m^2
  // The wheel as SCM soil sees it: a rigid cylinder of the tire's unloaded radius; width 0 when the
  // file gives none (then the vehicle cannot run on SCM).
  lowfi::ScmWheelShape scm_wheel;
  TmeasyParams tire;
  double tire_vertical_damping = 0;  // N s/m
  double total_mass() const;
};

FullVehicleSpec read_full_vehicle(const nlohmann::json& j, const std::string& source);
// `hmmwv`, or a JSON file's path.
FullVehicleSpec load_full_vehicle(const std::string& name_or_path);
std::string full_vehicle_preset_json(const std::string& name);  // "" when no such preset

class FullVehicle {
 public:
  // Builds the vehicle with its chassis frame's origin at `origin` (world, the chassis level).
  FullVehicle(const FullVehicleSpec& spec, const Vec3& origin, double ground_friction = 1.0);
  FullVehicle(const FullVehicle&) = delete;
  FullVehicle& operator=(const FullVehicle&) = delete;

  mb::MbSystem& system() { return *system_; }
  const mb::MbSystem& system() const { return *system_; }
  int chassis() const { return chassis_; }
  const std::vector<WishboneSide>& corners() const { return corners_; }  // front left, front right, ...
  bool has_steering() const { return spec_.has_steering; }
  // The driver's inputs against time (steering in [-1, 1], positive to the left; throttle and braking
  // in [0, 1]); none until set.
  void set_driver(DriverFunction driver) { driver_ = std::move(driver); }
  DriverInput driver_input(double t) const { return driver_(t); }
  bool has_powertrain() const { return spec_.has_powertrain; }
  const Driveline& driveline() const { return driveline_; }
  // Shifts gear by the gearbox input's speed; true when it changed (restart the integrator then).
  bool update_gear();
  // Puts the gearbox in `gear` (set_forward_speed: a vehicle that starts rolling).
  void set_gear(int gear);
  const PitmanArm& steering() const { return steering_; }  // with the Pitman-arm template
  const RackPinion& rack() const { return rack_; }         // with the rack-and-pinion template
  // The body the steered axle's tie rods end on: the Pitman arm's link or the rack.
  int steering_link() const { return spec_.rack_steering ? rack_.rack : steering_.link; }
  const FullVehicleSpec& spec() const { return spec_; }
  // Each tire's contact in the system's present state (on SCM: the held soil forces and the sinkage).
  std::vector<TireContact> contacts() const;
  // The wheels on SCM soil instead of the tires on rigid ground (before the integrator is made);
  // throws InputError when the spec's wheel has no width.
  void use_scm(const lowfi::ScmSoil& soil, const lowfi::ScmSettings& settings);
  const ScmWheelContact* scm() const { return scm_.get(); }
  // One soil step at the present state, time t (on SCM; nothing on rigid ground).
  void step_soil(double t);

 private:
  FullVehicleSpec spec_;
  std::unique_ptr<mb::MbSystem> system_;
  RigidGroundTire tire_;
  std::unique_ptr<ScmWheelContact> scm_;  // null: rigid ground
  int chassis_ = -1;
  std::vector<WishboneSide> corners_;
  PitmanArm steering_;
  RackPinion rack_;
  DriverFunction driver_ = [](double) { return DriverInput{}; };
  Driveline driveline_;
};

}  // namespace terracal::vehicle
