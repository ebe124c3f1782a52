#pragma once
// CRM behind the rigs' Terrain interface: a CrmSite settles its bed once (or loads it from the
// cache) and starts every terrain from it; CrmTerrain steps the CRM solver with the rig's bodies.
#include <filesystem>
#include <memory>

#include "core/terrain.hpp"
#include "highfi/crm/crm_run.hpp"
#include "highfi/crm/crm_run_check.hpp"
#include "highfi/crm/crm_solver.hpp"

namespace terracal {

// The soil surface of a bed: the mean height of its top layer of particles in the middle half of the
// bin (away from the walls' meniscus), plus half a spacing. Throws RunError for a bed with no
// particles there.
double bed_surface_height(const HostSoil& bed, const CrmScene& scene);

// The memory a CRM run of `scene` holds, estimated from its bin, spacing and effects before any
// particle exists (laid out as initial_bed, bin_marker_positions and crm_grid lay them out). On the
// host: the particles' state three times over (the site's settled bed, the solver's copy of it while
// the engine is made, and settling's start or download) and, on the CPU, the engine's arrays. On the
// GPU: the engine's arrays and the sort's scratch.
struct CrmMemoryNeed {
  double particles = 0, markers = 0, cells = 0;
  double host_bytes = 0, gpu_bytes = 0;
};
CrmMemoryNeed crm_memory_need(const CrmScene& scene, CrmDevice device);

class CrmTerrain final : public Terrain {
 public:
  CrmTerrain(const CrmScene& scene, CrmDevice device, const HostSoil& bed)
      : solver_(scene, device, &bed), health_(solver_) {}
  std::string description() const override;
  void step() override;
  double time() const override { return solver_.time(); }
  double time_step() const override { return solver_.time_step(); }
  const std::vector<BodyState>& bodies() const override { return solver_.bodies(); }
  const std::vector<BodyWrench>& wrenches() const override { return solver_.wrenches(); }
  // How much of the active soil is held at the density cap now.
  std::string numerics_note() const override;
  const CrmSolver& solver() const { return solver_; }

 private:
  CrmSolver solver_;
  CrmRunCheck health_;  // after solver_: made from it
};

class CrmSite final : public TerrainSite {
 public:
  // `base` holds the soil, bin, resolution, effects and settle time (its bodies are ignored); the
  // bed is settled now, or read from cache_dir when it holds one for the same soil, bin and numerics.
  CrmSite(const CrmScene& base, CrmDevice device, const std::filesystem::path& cache_dir);
  std::string name() const override { return "crm"; }
  std::string description() const override;
  double surface_height() const override { return surface_; }
  Vec3<double> gravity() const override { return base_.soil.gravity; }
  Vec3<double> centre() const override;
  double half_length() const override;
  double half_width() const override { return 0.5 * base_.bin.size.y; }
  std::unique_ptr<Terrain> make(std::vector<RigidBody> bodies, double duration) const override;
  const CrmScene& base() const { return base_; }
  bool bed_from_cache() const { return from_cache_; }
  std::size_t particles() const { return bed_.size(); }

 private:
  CrmScene base_;
  double requested_step_ = 0;  // the scene's time step as given (0: from the CFL limit with the bodies' speed)
  CrmDevice device_;
  HostSoil bed_;
  double surface_ = 0;
  bool from_cache_ = false;
};

}  // namespace terracal
