#pragma once
// The driveline's 1-D parts, as Chrono::Vehicle builds its shafts drivelines: shafts (one rotation,
// an inertia), couplings that tie shaft speeds linearly (gears, differentials) or tie a shaft to the
// spin of a body about an axis of another (a wheel on its upright), and torques between shafts
// (clutches) or on a shaft (an engine, a brake). Couplings are velocity constraints: they hold speeds,
// not angles, so shaft angles never wrap into the constraint equations.
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "highfi/multibody/constraint_rows.hpp"

namespace terracal::mb {

struct Shaft {
  std::string name;
  double inertia = 1;  // kg m^2
  double angle = 0;    // rad
  double speed = 0;    // rad/s
};

// sum_k c_k w_k = 0 over shafts. A gear of ratio r (w_out = r w_in): {out: 1, in: -r}. An open
// differential: {left: 1, right: 1, case: -2}.
struct ShaftLinkage {
  std::string name;
  std::vector<int> shafts;
  std::vector<double> coefficients;
};
ShaftLinkage gear(std::string name, int in, int out, double ratio);
ShaftLinkage differential(std::string name, int case_shaft, int left, int right);

// w_shaft = the spin of body j about body i's axis (a body-i frame direction): z . (w_j - w_i), world.
struct ShaftToBody {
  std::string name;
  int shaft = -1, i = -1, j = -1;
  Vec3 axis_i = Vec3::UnitZ();
  // The row over the bodies' velocities and the shaft's speed (placed by the system).
  ConstraintRow row(const std::vector<RigidBody>& bodies, Row6& shaft_part) const;
};

// A torque on a shaft as a function of time, angle and speed (an engine's map, a brake).
struct ShaftTorque {
  std::string name;
  int shaft = -1;
  std::function<double(double t, double angle, double speed)> torque;
};

// Torques between two shafts that depend on both speeds (a torque converter): returns the torques on a
// and on b.
struct ShaftPairTorque {
  std::string name;
  int a = -1, b = -1;
  std::function<std::pair<double, double>(double t, double wa, double wb)> torques;
};

// A friction clutch (or a brake between two shafts): the torque that drags shaft b towards shaft a's
// speed, c (w_a - w_b), bounded by +-max_torque. max_torque 0 is open; a large one locks it.
struct Clutch {
  std::string name;
  int a = -1, b = -1;
  double max_torque = 0;      // N m
  double slip_damping = 1e4;  // N m s/rad: how firmly a locked clutch holds the speeds together
  double torque(double wa, double wb) const;
};

}  // namespace terracal::mb
