#pragma once
// The double-wishbone suspension template, as Chrono::Vehicle's: per side a spindle (the wheel's
// carrier, turning about its y axis on the upright), an upright, an upper and a lower control arm
// hinged to the chassis, a tie rod (a distance constraint from the chassis or the steering link to
// the upright), a spring and a shock between the chassis and the lower arm. Hardpoints are given for
// the left side in the suspension's frame (x forward, y left, z up; the origin at the suspension's
// location on the chassis); the right side mirrors them (y -> -y).
#include <string>
#include <vector>

#include "core/json_object.hpp"
#include "highfi/multibody/mb_system.hpp"

namespace terracal::vehicle {

using mb::Mat3;
using mb::Vec3;

struct BodySpec {
  double mass = 1;
  Vec3 com = Vec3::Zero();
  Vec3 moments = Vec3::Ones();   // principal moments in the suspension frame, kg m^2
  Vec3 products = Vec3::Zero();  // Ixy, Ixz, Iyz
  Mat3 inertia() const;
};

struct ArmSpec {
  BodySpec body;
  Vec3 chassis_front = Vec3::Zero(), chassis_back = Vec3::Zero(), upright = Vec3::Zero();
};

struct DoubleWishboneSpec {
  std::string name = "double wishbone";
  BodySpec spindle, upright;
  double spindle_radius = 0.15, spindle_width = 0.06;  // m (drawing only)
  ArmSpec upper_arm, lower_arm;
  Vec3 tierod_chassis = Vec3::Zero(), tierod_upright = Vec3::Zero();
  Vec3 spring_chassis = Vec3::Zero(), spring_arm = Vec3::Zero();
  double spring_free_length = 0;
  std::vector<double> spring_deflection, spring_force;  // tension against extension, N (a table)
  Vec3 shock_chassis = Vec3::Zero(), shock_arm = Vec3::Zero();
  double shock_damping = 0;   // N s/m
  double axle_inertia = 0.4;  // kg m^2, the axle shaft
};

// Reads a suspension object (docs/formats.md, "Double-wishbone suspension"); errors name the key.
DoubleWishboneSpec read_double_wishbone(JsonObject o);

// One side built into a system: body indices, the spindle joint, the tie rod joint.
struct WishboneSide {
  int spindle = -1, upright = -1, upper_arm = -1, lower_arm = -1;
  int spindle_joint = -1, tierod_joint = -1;
  double side = 1;  // +1 left, -1 right
};

// Builds one side on `chassis`, whose frame is the world's at build time shifted by `location` (the
// suspension's origin in the chassis frame, with the chassis placed at `chassis_origin`). The tie rod's
// inner end is on `tierod_body` (the chassis, or a steering link).
WishboneSide build_double_wishbone(mb::MbSystem& s, const DoubleWishboneSpec& spec, int chassis, int tierod_body,
                                   const Vec3& chassis_origin, const Vec3& location, double side);

}  // namespace terracal::vehicle
