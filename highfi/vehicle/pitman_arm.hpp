#pragma once
// The Pitman-arm steering template, as Chrono::Vehicle's: a Pitman arm hinged to the chassis and turned
// by the steering gear, a steering link joined to the arm by a universal joint and held on the other
// side by an idler (a revolute-spherical joint: the link's point keeps its distance from the chassis
// point and stays in the plane normal to the idler's axis). The tie rods of the steered axle end on the
// link. The steering gear is a stiff servo on the arm's angle (steering input times the maximum angle).
// Points and directions are in the steering's frame, placed on the chassis by a location and a rotation.
#include "highfi/vehicle/double_wishbone.hpp"

namespace terracal::vehicle {

struct PitmanArmSpec {
  std::string name = "Pitman arm";
  BodySpec link, arm;
  Vec3 revolute_point = Vec3::Zero(), revolute_axis = Vec3::UnitZ();  // arm to chassis
  double max_angle = 0;                                               // rad, the arm's turn at full input
  Vec3 universal_point = Vec3::Zero(), universal_axis_arm = Vec3::UnitZ(), universal_axis_link = Vec3::UnitX();
  Vec3 idler_chassis = Vec3::Zero(), idler_link = Vec3::Zero(), idler_axis = Vec3::UnitZ();
  Vec3 location = Vec3::Zero();                 // the steering frame's origin in the chassis frame
  mb::Quat orientation = mb::Quat::Identity();  // and its rotation
  double servo_stiffness = 1e6;                 // N m/rad of the steering gear's hold on the arm's angle
  double servo_damping = 1e4;                   // N m s/rad
};

PitmanArmSpec read_pitman_arm(JsonObject o);

struct PitmanArm {
  int link = -1, arm = -1, revolute = -1;
  Vec3 axis_chassis = Vec3::UnitZ();  // the revolute's axis in the chassis frame
};

// Builds the steering on `chassis` (whose frame is placed at `chassis_origin`, unrotated).
PitmanArm build_pitman_arm(mb::MbSystem& s, const PitmanArmSpec& spec, int chassis, const Vec3& chassis_origin);

// The arm's angle about its hinge (0 as built), rad.
double pitman_arm_angle(const mb::MbSystem& s, const PitmanArm& p);

// Adds the steering gear: a servo that turns the arm to -input(t) times the maximum angle (input in
// [-1, 1], positive turning left; the arm turns clockwise seen from above to steer left, as in
// Chrono's layouts with the arm on the left).
void add_steering_servo(mb::MbSystem& s, const PitmanArmSpec& spec, const PitmanArm& p,
                        std::function<double(double)> input);

}  // namespace terracal::vehicle
