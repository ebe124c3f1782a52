#pragma once
// The rack-and-pinion steering template, as Chrono::Vehicle's: a rack (the steering link) that slides
// along its axis in a prismatic joint on the chassis, the steered axle's tie rods ending on it. The
// pinion turns it: a stiff servo holds the rack's travel at the input times the pinion's radius times
// its largest angle. Points and directions are in the steering's frame, placed on the chassis by a
// location and a rotation.
#include <functional>

#include "core/json_object.hpp"
#include "highfi/multibody/mb_system.hpp"
#include "highfi/vehicle/double_wishbone.hpp"

namespace terracal::vehicle {

struct RackPinionSpec {
  std::string name = "rack-and-pinion";
  BodySpec rack;
  // The rack's slide; a positive input (steering left) moves the rack along it.
  Vec3 axis = Vec3::UnitY();
  double pinion_radius = 0;  // m
  double max_angle = 0;      // rad, the pinion's turn at full input
  Vec3 location = Vec3::Zero();
  mb::Quat orientation = mb::Quat::Identity();
  double servo_stiffness = 1e7;  // N/m of the pinion's hold on the rack's travel
  double servo_damping = 1e5;    // N s/m
  double max_travel() const { return pinion_radius * max_angle; }
};

RackPinionSpec read_rack_pinion(JsonObject o);

struct RackPinion {
  int rack = -1, prismatic = -1;
  Vec3 axis_chassis = Vec3::UnitY();  // the slide in the chassis frame
  Vec3 built_at = Vec3::Zero();       // the rack's centre as built, in the chassis frame (from its centre of mass)
};

// Builds the steering on `chassis` (whose frame is placed at `chassis_origin`, unrotated).
RackPinion build_rack_pinion(mb::MbSystem& s, const RackPinionSpec& spec, int chassis, const Vec3& chassis_origin);

// The rack's travel along its axis from where it was built, m.
double rack_travel(const mb::MbSystem& s, const RackPinion& r);

// Adds the pinion: a servo that moves the rack to input(t) times the largest travel (input in [-1, 1]).
void add_rack_servo(mb::MbSystem& s, const RackPinionSpec& spec, const RackPinion& r,
                    std::function<double(double)> input);

}  // namespace terracal::vehicle
