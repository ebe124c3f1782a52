#pragma once
// A suspension's kinematics from its hardpoints: camber and toe (and the wheel centre's lateral
// motion) against wheel travel, by a kinematic solve: the chassis held, the wheel centre put at each
// height in turn and the joints assembled around it. Conventions: camber is positive with the wheel's
// top outwards, toe positive with its front inwards (toe-in); travel positive upwards (bump).
#include <vector>

#include "highfi/vehicle/double_wishbone.hpp"

namespace terracal::vehicle {

struct WheelAlignment {
  double travel = 0;   // m, the wheel centre's rise from the design position
  double camber = 0;   // rad
  double toe = 0;      // rad
  double lateral = 0;  // m, the wheel centre's outward motion
};

// The alignment of a wheel whose spindle has axis `axis` (world, along the spindle's y) on `side`.
WheelAlignment alignment(const Vec3& axis, double side);

// Camber, toe and lateral motion at each travel (any order), for one side of the suspension.
std::vector<WheelAlignment> double_wishbone_kinematics(const DoubleWishboneSpec& spec,
                                                       const std::vector<double>& travels, double side = 1);

}  // namespace terracal::vehicle
