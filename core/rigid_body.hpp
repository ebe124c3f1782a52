#pragma once
// A rigid body as the terrains see it: its shape, where it starts, its motion program (each degree
// of freedom prescribed or free under the soil's wrench, gravity and applied loads) and its mass
// properties. CRM scenes, the SCM terrain and the rigs all describe bodies this way.
#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "core/body_shape.hpp"
#include "core/quat.hpp"
#include "core/vec.hpp"

namespace terracal {

// Each of the six degrees of freedom is prescribed (constant velocity) or free (dynamic).
// One piece of a prescribed velocity schedule: these velocities for `duration` seconds.
struct MotionSegment {
  double duration = 0;
  Vec3<double> linear_velocity{}, angular_velocity{};
};

struct BodyMotion {
  Vec3<double> linear_velocity{}, angular_velocity{};  // world frame; the initial velocity of free DOFs
  std::array<bool, 6> free{};                          // x, y, z, rx, ry, rz
  // Prescribed velocities as piecewise-constant functions of time (t = 0 when the bodies enter,
  // after settling); after the last segment the prescribed axes hold still. Empty: the constant
  // velocities above. Free axes ignore the schedule.
  std::vector<MotionSegment> schedule;
  bool moves() const;
  bool any_free() const;
  // The prescribed velocities at time t.
  Vec3<double> linear_at(double t) const;
  Vec3<double> angular_at(double t) const;
  // The largest prescribed speed at distance `radius` from the body's centre (for the CFL step).
  double max_speed(double radius) const;
};

struct RigidBody {
  std::string name;
  BodyShape shape;
  Vec3<double> position{};
  Quat orientation{};
  BodyMotion motion;
  double mass = 0;
  Vec3<double> inertia{};                          // principal moments in the body frame
  Vec3<double> applied_force{}, applied_torque{};  // world frame, added to the soil's wrench and gravity
  // [s] The body's weight and applied force grow linearly from zero over this time, as a bevameter's
  // ram puts its load on gradually; 0: all at once. A dead load dropped at once drives a body past
  // its static sinkage and leaves it moving when the test starts (results/plate_bin_check, twelfth study).
  double load_ramp = 0;
  double load_fraction(double t) const { return load_ramp > 0 ? std::min(1.0, std::max(0.0, t) / load_ramp) : 1.0; }
  double bounding_radius() const;  // of the shape about the body origin
};

// The state of a body and the wrench of the soil on it.
struct BodyState {
  Vec3<double> position{};
  Quat orientation{};
  Vec3<double> velocity{}, omega{};
};

struct BodyWrench {
  Vec3<double> force{}, torque{};  // of the soil on the body; torque about the body position
};

// One explicit update of a body's free degrees of freedom (and of the prescribed ones from its
// schedule): from `base` over h with the rates evaluated at state `at` under the soil's wrench w,
// gravity and the applied loads; t_out is the time at the end of the update. Called twice per step
// it is the midpoint rule the CRM solver uses; the SCM terrain uses it for the velocities of a
// symplectic Euler step.
BodyState advance_body(const RigidBody& body, const BodyState& base, const BodyState& at, const BodyWrench& w,
                       const Vec3<double>& gravity, double h, double t_out);

}  // namespace terracal
