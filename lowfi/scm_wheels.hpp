#pragma once
// SCM soil under wheels that another integrator moves: the explicit co-simulation of Chrono's vehicle
// on SCM. Every SCM step (settings.time_step) the vehicle gives each wheel's present state (world
// position of its centre, orientation, linear and angular velocity); the soil advances one step at
// those poses (plastic sinkage, Janosi shear displacement over the step) and returns the soil's wrench
// on each wheel, which the vehicle holds as an applied wrench until the next SCM step.
//
// The wheels are bodies of an ScmTerrain with every degree of freedom driven from outside
// (ScmTerrain::step_at): the terrain integrates nothing, so the vehicle's integrator (IDAS, any
// step size) alone moves them. Holding the wrench over a step makes the elastic contact's
// oscillation grow by about (omega dt)^2 / 4 of its amplitude per step (omega^2 = Ke x contact area /
// the mass on the wheel, dt the SCM step) where the soil's damping (effect `damping`) does not drain more.
#include <cstddef>
#include <string>
#include <vector>

#include "core/rigid_body.hpp"
#include "lowfi/scm_soil.hpp"
#include "lowfi/scm_terrain.hpp"

namespace terracal::lowfi {

// A wheel as the soil sees it: a rigid cylinder about its body y axis (the spin axis), centred on the
// body's position, optionally with straight grousers across its width (as the wheel rig's wheel).
struct ScmWheelShape {
  std::string name = "wheel";  // for messages
  double radius = 0, width = 0;
  int grouser_count = 0;
  double grouser_height = 0, grouser_thickness = 0;
};
// Throws InputError naming the wheel, the value and its allowed range.
void validate(const ScmWheelShape& w);

class ScmWheels {
 public:
  // An undisturbed flat patch (settings.surface_height) with the wheels above it until the first step.
  // Throws InputError for bad settings, soil or wheel shapes.
  ScmWheels(const ScmSoil& soil, const ScmSettings& settings, const std::vector<ScmWheelShape>& wheels);

  // One SCM step at the wheels' present states (one per wheel, in the constructor's order; world
  // frame, the orientation of each wheel's body frame, which is normalised here). Throws RunError
  // for a state count other than size(), and naming the wheel for a non-finite value, a zero
  // quaternion or a wheel beyond the grid's integer range (the soil is then unchanged); the
  // terrain's own RunErrors (NoBekkerStrength) pass through.
  void step(const std::vector<BodyState>& wheels);

  std::size_t size() const { return shapes_.size(); }
  const std::vector<ScmWheelShape>& shapes() const { return shapes_; }
  double time_step() const { return terrain_.time_step(); }
  double time() const { return terrain_.time(); }  // steps taken x time_step
  // After step(): the soil's wrench on each wheel (world force, torque about the wheel's centre);
  // exactly zero for a wheel out of contact. Zero before the first step.
  const std::vector<BodyWrench>& wrenches() const { return terrain_.wrenches(); }
  // After step(): how deep wheel w's lowest node in contact lies below the soil's undisturbed level
  // [m] (0 out of contact), and the area of its contact nodes (projected, [m^2]).
  double sinkage(std::size_t w) const { return terrain_.last_step().body_max_sinkage.at(w); }
  double contact_area(std::size_t w) const { return terrain_.last_step().body_contact_area.at(w); }
  // The soil itself (node sinkages, step statistics, volumes).
  const ScmTerrain& terrain() const { return terrain_; }

 private:
  std::vector<ScmWheelShape> shapes_;
  ScmTerrain terrain_;
};

}  // namespace terracal::lowfi
