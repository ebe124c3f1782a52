#pragma once
// CrmSolver: the CRM time loop on one engine (CPU or CUDA). It owns the rigid bodies (prescribed
// or dynamic degrees of freedom, integrated with the same midpoint rule as the soil) and returns
// the wrench of the soil on each body. Settling and caching of beds live in crm_run.hpp.
#include <cstdint>
#include <memory>
#include <vector>

#include "highfi/crm/crm_scene.hpp"
#include "highfi/crm/sph_engine.hpp"

namespace terracal {

// The initial bed: particles on a lattice of spacing d0 filling the bin to fill_height, at rest,
// with the lithostatic stress sigma_zz = -rho |g| depth and sigma_xx = sigma_yy = nu/(1-nu) sigma_zz.
HostSoil initial_bed(const CrmScene& scene);

// Moves every particle of `soil` by a uniform random offset in [-amplitude, amplitude] along each
// axis, drawn from a generator seeded with `seed` (the same seed gives the same bed). Settling starts
// from such a bed: one released from the exact lattice stays still for 0.15-0.4 s, then rearranges in
// a burst that takes about a second to die out (results/crm_settling).
void jitter_positions(HostSoil& soil, double amplitude, std::uint64_t seed);

// Where settling starts: initial_bed moved by scene.settle_jitter spacings at most, drawn with
// scene.settle_seed (a settled bed is a function of its scene, and is cached as one).
HostSoil settling_start(const CrmScene& scene);

class CrmSolver {
 public:
  // `bed` is the soil to start from (a settled bed); empty means initial_bed(scene).
  CrmSolver(const CrmScene& scene, CrmDevice device, const HostSoil* bed = nullptr);

  void step();
  double time() const { return time_; }
  long steps() const { return steps_; }
  double time_step() const { return scene_.numerics.time_step; }
  const CrmScene& scene() const { return scene_; }
  SphEngine& engine() { return *engine_; }
  const SphEngine& engine() const { return *engine_; }

  // Scene bodies (index as in scene.bodies); the bin's walls are reported separately.
  const std::vector<BodyState>& bodies() const { return bodies_; }
  const std::vector<BodyWrench>& wrenches() const { return wrenches_; }
  const BodyWrench& wall_wrench() const { return wall_wrench_; }
  // Work the bodies have done on the soil since the solver was made [J] (midpoint rule: the stage's
  // wrench times the bodies' half-step velocities); the bin's walls are at rest and do none.
  double work_on_soil() const { return work_on_soil_; }

  SoilStats stats() const { return engine_->stats(); }
  HostSoil soil() const;
  // Restores the state saved by a checkpoint (same scene): soil, bodies, time and step count.
  void restore(const HostSoil& soil, const std::vector<BodyState>& bodies, double time, long steps);

  // Body-frame marker positions of scene body b (for snapshots).
  const std::vector<Vec3<double>>& body_markers(std::size_t b) const { return body_local_[b]; }

 private:
  std::vector<BodyPose<double>> poses(const std::vector<BodyState>& states) const;

  CrmScene scene_;
  std::unique_ptr<SphEngine> engine_;
  std::vector<BodyState> bodies_;
  std::vector<BodyWrench> wrenches_;
  BodyWrench wall_wrench_;
  std::vector<std::vector<Vec3<double>>> body_local_;
  double time_ = 0;
  long steps_ = 0;
  double work_on_soil_ = 0;
};

// What an effect's before_step hook sees of a step (CrmEffect::before_step): the scene's bodies,
// their states at the start of the step, and the engine.
struct CrmStepView {
  const std::vector<CrmBody>& bodies;
  const std::vector<BodyState>& states;
  SphEngine& engine;
};

// The engine's constants for a scene (shared by the solver and tests).
SphConstants<double> crm_constants(const CrmScene& scene);
GridGeometry<double> crm_grid(const CrmScene& scene);

// The named effects' constants in the precision T (CrmEffect::constants).
template <class T>
CrmEffectConstants<T> crm_effect_constants(const CrmScene& sc) {
  CrmEffectConstants<T> c;
  const CrmEffectInput in{sc.soil, sc.numerics.smoothing_length(), sc.numerics.spacing};
  sc.effects.named.for_each_named([&](auto tag) {
    using E = typename decltype(tag)::type;
    c.template get<E>() = E::template constants<T>(sc.effects.template of<E>(), in);
  });
  return c;
}

}  // namespace terracal
