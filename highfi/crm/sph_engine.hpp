#pragma once
// The CRM particle engine seen from the host: a precision- and device-independent interface in
// double precision. Implementations: the CPU (OpenMP) backend in float64 or float32 and the CUDA
// backend in float32; all run the same functors (soil_stage.hpp, marker_stage.hpp, sph_pair.hpp).
#include <array>
#include <memory>
#include <string>
#include <vector>

// Only the data layouts and the effects' registry: the stage functors (and their CPU SIMD code,
// built for this CPU) stay inside the backends, so code that drives the solver does not depend on
// how it was compiled.
#include "highfi/crm/effects/crm_effects.hpp"
#include "highfi/crm/sph_fields.hpp"

namespace terracal {

enum class CrmDevice { kCpu, kCuda };
enum class CrmPrecision { kDouble, kFloat };

struct HostSoil {
  std::vector<Vec4<double>> pos, vel, s0, s1;  // layout of SoilArrays
  // The effects' records by slot (SoilArrays::record); empty where the effect is off (then zero).
  std::array<std::vector<Vec4<double>>, kCrmRecordSlots> records;
  std::vector<int> ids;  // original particle numbers (the arrays are kept sorted by cell)
  std::size_t size() const { return pos.size(); }
  template <class E>
  std::vector<Vec4<double>>& record() {
    static_assert(E::kRecord, "this effect keeps no record per particle");
    return records[kRecordSlot<E>];
  }
  template <class E>
  const std::vector<Vec4<double>>& record() const {
    static_assert(E::kRecord, "this effect keeps no record per particle");
    return records[kRecordSlot<E>];
  }
};

struct HostMarkers {
  std::vector<Vec4<double>> pos;       // world position, w = density the soil sees
  std::vector<Vec4<double>> local;     // body frame, w = body index
  std::vector<Vec4<double>> wall_vel;  // w = 1 for markers of moving bodies
  std::vector<Vec4<double>> normal;    // body frame: unit normal towards the soil, w = depth (empty or w = 0: none)
  std::size_t size() const { return pos.size(); }
};

struct EngineSetup {
  SphConstants<double> constants;
  CrmEffectSet effects;  // the named effects, and their constants in each precision (unused where off)
  CrmEffectConstants<double> effect_constants_double;
  CrmEffectConstants<float> effect_constants_float;
  template <class T>
  const CrmEffectConstants<T>& effect_constants() const {
    if constexpr (sizeof(T) == sizeof(double))
      return effect_constants_double;
    else
      return effect_constants_float;
  }
  GridGeometry<double> grid;
  HostSoil soil;
  HostMarkers markers;
  int bodies = 1;
  // How far (per axis) a particle or marker may move out of the cell it was sorted into before the
  // next sort, for cells of 2h (1 + skin) / reach: 2 h skin, a little less for round-off. 0: sort at
  // every step (and every pose of a moving body), with cells of exactly 2h / reach.
  double sort_drift = 0;
  // The soil's room: a particle whose centre gets further than half a spacing into the bin's walls
  // has broken through the boundary (a violent impact can squeeze one in) and is marked lost.
  Vec3<double> room_lo{-1e30, -1e30, -1e30}, room_hi{1e30, 1e30, 1e30};
};

// Sums over the soil in double precision (for progress, tests and stability checks).
struct SoilStats {
  double mass = 0, kinetic_energy = 0;
  Vec3<double> momentum{};
  Vec3<double> first_moment{};  // sum of m x: the soil's potential energy is -g . first_moment
  double max_speed = 0;
  long nonfinite = 0, lost = 0, frozen = 0;
  long at_density_cap = 0;  // active particles whose density is held at density_cap (soil_model.hpp)
};

// How the engine's sorts of the markers by cell went: every marker sorted, or only the moving
// bodies' (merged with the fixed ones: the same order, sph_sort.hpp).
struct SortCounts {
  long markers_full = 0, markers_merged = 0;
  long soil = 0;            // sorts of the soil by cell
  long markers_moved = 0;   // poses at which the markers kept their cells (sort_drift > 0)
};

class SphEngine {
 public:
  virtual ~SphEngine() = default;
  virtual std::string description() const = 0;
  virtual std::size_t soil_count() const = 0;
  virtual std::size_t marker_count() const = 0;
  virtual std::size_t device_bytes() const = 0;
  // Places body markers at the given poses (index = body) and re-sorts them when any moves.
  virtual void set_poses(const std::vector<BodyPose<double>>& poses) = 0;
  // Freezes soil outside the boxes (active_domain); an empty list activates every particle.
  virtual void set_active(const std::vector<ActiveBox<double>>& boxes) = 0;
  // Sorts the soil by cell; called once per step before the stages.
  virtual void begin_step() = 0;
  // Stage 0: A -> B over dt/2; stage 1: B -> A over dt (midpoint rule). Returns the wrench of the soil
  // on each body, about the body's pose centre: 6 doubles per body (force, torque). Stage 0 with
  // want_wrench false (no body has a free degree of freedom: nothing reads it) returns zeros and does
  // not wait for the device; stage 1 always sums it.
  virtual std::vector<double> stage(int which, double dt, bool want_wrench) = 0;
  virtual SoilStats stats() const = 0;
  virtual SortCounts sort_counts() const = 0;
  virtual void download(HostSoil& soil) const = 0;
  virtual void upload(const HostSoil& soil) = 0;
};

std::unique_ptr<SphEngine> make_cpu_engine(const EngineSetup& setup, CrmPrecision precision);
// Throws RunError when the build has no CUDA or no device is present.
std::unique_ptr<SphEngine> make_cuda_engine(const EngineSetup& setup);
bool cuda_engine_available(std::string* why = nullptr);

}  // namespace terracal
