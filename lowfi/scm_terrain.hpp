#pragma once
// The Soil Contact Model terrain (docs/architecture.md, "SCM and Wong-Reece"), in the manner of
// Chrono's SCM: a sparse grid of nodes keyed by integer coordinates (only touched nodes are stored,
// the patch is unbounded), one vertical ray per node under each body's bounding box, contact
// patches with their Bekker width, elastic-plastic pressure (stiffness Ke up to the Bekker yield,
// plastic sinkage remembered) and Janosi shear from each node's accumulated shear displacement.
//
// Effects (named in the settings; a name not given costs nothing): lowfi/effects/, one file each.
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/errors.hpp"
#include "core/rigid_body.hpp"
#include "core/shape_raycast.hpp"
#include "core/terrain.hpp"
#include "lowfi/contact_patches.hpp"
#include "lowfi/effects/scm_effects.hpp"
#include "lowfi/scm_nodes.hpp"
#include "lowfi/scm_soil.hpp"

namespace terracal::lowfi {

// A set whose pressure-sinkage law has no strength for a contact as narrow as the one a body made:
// Kc/b + Kphi <= 0 (a negative Kc fitted on wider plates). The run cannot go on with this set.
struct NoBekkerStrength : RunError {
  using RunError::RunError;
};

// Names the effects in `names` (with their default settings); throws InputError naming `key` and an
// unknown name.
ScmEffectChoice parse_scm_effects(const std::vector<std::string>& names, const std::string& key);

struct ScmSettings {
  double grid = 0.01;       // node spacing [m]
  double time_step = 1e-3;  // [s]
  Vec3<double> gravity{0, 0, -9.81};
  double surface_height = 0;  // the undisturbed surface is the plane z = surface_height
  bool coarse_rays = true;    // cull rays far above the soil with a coarse pass (same result, fewer rays)
  ScmEffectChoice effects;
};
// Throws InputError naming the setting, its value and the allowed range.
void validate(const ScmSettings& s, const ScmSoil& soil);

struct ScmStepStats {
  int contact_nodes = 0, patches = 0, rays = 0;
  double contact_area = 0, max_sinkage = 0;
  std::vector<double> patch_bekker_width;
  std::vector<double> body_contact_area;  // per body [m^2]
  std::vector<double> body_max_sinkage;   // per body: its deepest node below the undisturbed level [m]
};

class ScmTerrain final : public Terrain {
 public:
  ScmTerrain(const ScmSoil& soil, const ScmSettings& settings, std::vector<RigidBody> bodies);
  // A copy's contact_nodes_ would point into the original's nodes; a move keeps them (the map's
  // nodes move with it).
  ScmTerrain(const ScmTerrain&) = delete;
  ScmTerrain& operator=(const ScmTerrain&) = delete;
  ScmTerrain(ScmTerrain&&) = default;
  ScmTerrain& operator=(ScmTerrain&&) = default;

  std::string description() const override;
  void step() override;
  // Co-simulation (lowfi/scm_wheels.hpp): the bodies are where another integrator put them. Sets
  // every body's state (one per body, in order; the orientation is normalised), then advances the
  // soil one step at those poses and velocities (sinkage, shear displacement over time_step) and
  // evaluates the wrenches there. Nothing is integrated: the bodies' motion programs, masses and
  // loads are not used, nor is the stability check of step(). Throws RunError naming the body for a
  // state count other than the bodies', a non-finite or zero-length value, or a body beyond the
  // grid's integer range; the terrain is then unchanged.
  void step_at(const std::vector<BodyState>& states);
  double time() const override { return time_; }
  double time_step() const override { return settings_.time_step; }
  const std::vector<BodyState>& bodies() const override { return states_; }
  const std::vector<BodyWrench>& wrenches() const override { return wrenches_; }

  const ScmSoil& soil() const { return soil_; }
  const ScmSettings& settings() const { return settings_; }
  const ScmStepStats& last_step() const { return stats_; }
  std::size_t stored_nodes() const { return nodes_.size(); }
  // The soil surface at grid node (i, j) when no body presses on it.
  double free_surface(int i, int j) const;
  // Soil volumes over every stored node [m^3]: pushed down plastically (sum of z_p g^2) and piled
  // up by bulldozing (sum of the positive and negative level offsets g^2). Bulldozing conserves
  // them: what the bodies push down reappears around them.
  struct Volumes {
    double pushed_down = 0, piled_up = 0;
  };
  Volumes volumes() const;
  // Stored node (i, j), or nullptr if never touched.
  const ScmNode* node(int i, int j) const;
  // Every stored node (for snapshots of the surface).
  const ScmNodeGrid& grid() const { return nodes_; }

 private:
  // A node under a body whose underside is below the soil's free surface there.
  struct Hit {
    int i, j, body;
    double level;         // height of the body's underside above the node
    Vec3<double> normal;  // outward normal of the body's underside (from neighbouring rays)
  };
  // The vertical rays under one body, in its frame: its window of grid nodes (i0 + ii, j0 + jj) for
  // ii < nx, jj < ny; each ray starts at height z0 below the body and reaches t_max up to the
  // highest soil, from row(jj) + ii step_i along dir (the origins are affine in (ii, jj), so one
  // rotation serves them all, and a node's ray is the same whichever pass casts it).
  struct RayGrid {
    int i0 = 0, j0 = 0, nx = 0, ny = 0;
    double z0 = 0, t_max = 0;
    ShapeRaycaster::Direction dir;
    Vec3<double> o00{}, step_i{}, step_j{};
    Vec3<double> row(int jj) const { return o00 + double(jj) * step_j; }
  };
  void cast_rays(std::vector<Hit>& hits);
  bool ray_grid(std::size_t body, double top, RayGrid& r) const;
  void select_rays(std::size_t body, const RayGrid& r, double top);
  void cast_selected(std::size_t body, const RayGrid& r);
  void add_hits(std::size_t body, const RayGrid& r, double top, std::vector<Hit>& hits) const;
  void contact(const std::vector<Hit>& candidates);  // candidates: hits below the highest soil
  void select_pressed(const std::vector<Hit>& candidates);
  void check_bekker_strength(const std::vector<Hit>& hits, const ContactPatches& patches) const;
  void press(const Hit& hit, ScmNode& n, double bekker_width, double& displaced);
  void release_left_nodes();
  void check_step() const;
  void update_contact();  // rays, contact and wrenches at the current poses (step() then checks them)

  ScmSoil soil_;
  ScmSettings settings_;
  double tan_phi_ = 0;
  std::vector<RigidBody> bodies_;
  std::vector<ShapeRaycaster> shapes_;
  std::vector<BodyState> states_;
  std::vector<BodyWrench> wrenches_;
  ScmNodeGrid nodes_;
  // Nodes in contact at the last step. Pointers into nodes_, which never erases, so they stay valid
  // (and they save a hash lookup per node and step when the nodes are released).
  std::vector<ScmNode*> contact_nodes_;
  // Working memory of a step, kept between steps so that a step allocates nothing once warm.
  struct Scratch {
    std::vector<double> level;            // cast_rays: per node of a body's window, the underside's height (+inf: none)
    std::vector<char> near, wanted;       // cast_rays: coarse nodes near the soil; the nodes to cast (empty: all)
    std::vector<Hit> hits;                // cast_rays: the candidates
    std::vector<RayGrid> windows;         // cast_rays: the node windows of the bodies near the soil
    std::vector<Hit> pressed;             // contact: the hits below their node's free surface ...
    std::vector<ScmNode*> pressed_nodes;  // ... and their nodes
    std::vector<GridIndex> pressed_at;
    ContactPatches patches;
    std::vector<double> displaced;  // plastic volume pushed aside per patch
  } scratch_;
  ScmStepStats stats_;
  double time_ = 0;
  long steps_ = 0;
};

// An unbounded flat SCM patch: every terrain it makes starts undisturbed.
class ScmSite final : public TerrainSite {
 public:
  ScmSite(const ScmSoil& soil, const ScmSettings& settings) : soil_(soil), settings_(settings) {
    validate(settings_, soil_);
  }
  std::string name() const override { return "scm"; }
  std::string description() const override;
  double surface_height() const override { return settings_.surface_height; }
  Vec3<double> gravity() const override { return settings_.gravity; }
  std::unique_ptr<Terrain> make(std::vector<RigidBody> bodies, double) const override {
    return std::make_unique<ScmTerrain>(soil_, settings_, std::move(bodies));
  }
  const ScmSoil& soil() const { return soil_; }
  const ScmSettings& settings() const { return settings_; }

 private:
  ScmSoil soil_;
  ScmSettings settings_;
};

}  // namespace terracal::lowfi
