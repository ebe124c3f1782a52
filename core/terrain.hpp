#pragma once
// Terrain: the soil seen by a rig (docs/architecture.md, "Terrain"). It owns the rigid bodies a rig gave it
// (shape, motion program, mass), advances soil and bodies together one step at a time and reports
// the wrench of the soil on each body. CRM (highfi) and SCM (lowfi) implement it; rigs never know
// which one they drive. Bodies integrate inside the terrain because CRM couples them within its
// midpoint stages; the rig decides what is prescribed and what is free.
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "core/rigid_body.hpp"

namespace terracal {

class Terrain {
 public:
  virtual ~Terrain() = default;
  virtual std::string description() const = 0;
  virtual void step() = 0;
  virtual double time() const = 0;  // simulated seconds since the bodies entered
  virtual double time_step() const = 0;
  virtual const std::vector<BodyState>& bodies() const = 0;
  virtual const std::vector<BodyWrench>& wrenches() const = 0;
  // What the terrain's numerics say about the run so far, for the log (empty: nothing to say).
  virtual std::string numerics_note() const { return {}; }
};

// A soil site before any body is placed: where its undisturbed surface is and how much room it
// offers, so that a rig can place its bodies; then a terrain with those bodies. A CRM site settles
// (or loads) its bed once and starts every terrain from it; an SCM site is an unbounded flat patch.
class TerrainSite {
 public:
  virtual ~TerrainSite() = default;
  virtual std::string name() const = 0;         // "crm", "scm": for file names and reports
  virtual std::string description() const = 0;  // resolution and effects, for reports
  virtual double surface_height() const = 0;    // z of the undisturbed surface
  virtual Vec3<double> gravity() const = 0;
  // The centre of the free surface (x, y) and how far from it a body may reach in x and y before
  // the bin's walls disturb it (infinite for SCM).
  virtual Vec3<double> centre() const { return {0, 0, surface_height()}; }
  virtual double half_length() const { return std::numeric_limits<double>::infinity(); }
  virtual double half_width() const { return std::numeric_limits<double>::infinity(); }
  // A terrain with these bodies; `duration` is how long the rig will run it (CRM keeps it as its
  // scene's duration; its step is sized from the bodies' prescribed speeds, and the rigs check that
  // the bodies have room with rigs::check_fits).
  virtual std::unique_ptr<Terrain> make(std::vector<RigidBody> bodies, double duration) const = 0;
};

}  // namespace terracal
