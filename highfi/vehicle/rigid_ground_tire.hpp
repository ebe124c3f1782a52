#pragma once
// A TMeasy tire on flat rigid ground (z = 0) with friction: the wheel is a disc of the unloaded radius
// in the spindle's plane; where it dips below the ground, the vertical force is k_t delta + d_t
// delta' (the damping fading in over the first 3 mm), and the steady combined-slip TMeasy forces
// (core/vehicle/tmeasy.hpp) act at the contact point along the wheel's heading and lateral directions, scaled by the
// ground's friction over the one the curves were measured on. Rolling resistance is a torque against the spin, smoothed
// over 0.1 rad/s. The tread's relaxation is not modelled here (steady slips).
#include "core/vehicle/tmeasy.hpp"
#include "highfi/multibody/force_elements.hpp"

namespace terracal::vehicle {

struct TireContact {
  bool touching = false;
  double deflection = 0;              // m
  double fx = 0, fy = 0, fz = 0;      // N, heading, lateral, normal
  double sx = 0, sy = 0;              // slips
  double sinkage = 0;                 // m below the undisturbed soil (0 on rigid ground)
  mb::Vec3 point = mb::Vec3::Zero();  // contact point, world
};

// The deflection over which the tire's vertical damping fades in from zero (m).
inline constexpr double kDampingFadeDeflection = 0.003;

struct RigidGroundTire {
  TmeasyParams params;
  double vertical_damping = 0;  // N s/m
  double friction = 1;          // the ground's friction over the one of the curves
  // The tire's wrench on the spindle body (spin axis: the body's y), added to w.
  TireContact apply(const mb::RigidBody& spindle, mb::Wrench& w) const;
};

}  // namespace terracal::vehicle
