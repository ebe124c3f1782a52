#pragma once
// The steering's kinematics: the steered wheels' angles against the steering's position (the Pitman
// arm's angle or the rack's travel), by a kinematic solve (the chassis held, the arm turned or the rack
// moved and held, each wheel centre held at its design height), and
// the Ackermann error: how far the outer wheel's angle is from the one that shares the inner wheel's
// turning centre on the rear axle's line, cot(outer) - cot(inner) = track / wheelbase.
#include <vector>

#include "highfi/vehicle/full_vehicle.hpp"

namespace terracal::vehicle {

struct SteerAngles {
  double position = 0;         // the Pitman arm's angle (rad) or the rack's travel (m)
  double left = 0, right = 0;  // the steered wheels' angles, rad, positive turning left
  double ackermann_error = 0;  // outer wheel's angle minus the Ackermann one, rad
};

// A wheel's steer angle from its spindle (spin axis along the body's y), positive turning left.
double steer_angle(const mb::RigidBody& spindle);

// The Ackermann error for a left and a right wheel angle, a track and a wheelbase.
double ackermann_error(double left, double right, double track, double wheelbase);

// The steering's position for a steering input in [-1, 1] (positive to the left): the arm's angle
// -input max_angle, or the rack's travel input x its largest travel.
double steering_position(const FullVehicleSpec& spec, double input);
// The steering's present position in a vehicle.
double steering_position(const FullVehicle& v);

// For each steering position, the first steered axle's wheel angles with every wheel centre `travel` above its
// design height (the ride height; bump steer turns the wheels with it); the track is that axle's
// wheel centres' distance, the wheelbase the distance from it to the last axle.
std::vector<SteerAngles> steering_kinematics(const FullVehicleSpec& spec, const std::vector<double>& positions,
                                             double travel = 0);

// The radius of the path of the last axle's centre that the steered wheels' angles predict when no
// tire slips: each front wheel's axis meets the rear axle's line at its own centre, and the path's
// radius is the mean of the two.
double predicted_turn_radius(double left, double right, double track, double wheelbase);

}  // namespace terracal::vehicle
