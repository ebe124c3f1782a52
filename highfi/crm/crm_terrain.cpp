#include "highfi/crm/crm_terrain.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/errors.hpp"

namespace terracal {

double bed_surface_height(const HostSoil& bed, const CrmScene& scene) {
  const double d0 = scene.numerics.spacing;
  const double length = scene.bin.fill_length > 0 ? scene.bin.fill_length : scene.bin.size.x;
  const double cx = 0.5 * length, cy = 0.5 * scene.bin.size.y, hx = 0.25 * length, hy = 0.25 * scene.bin.size.y;
  auto middle = [&](const Vec4<double>& p) { return std::abs(p.x - cx) < hx && std::abs(p.y - cy) < hy; };
  double top = -1e300;
  for (const auto& p : bed.pos)
    if (middle(p)) top = std::max(top, p.z);
  double sum = 0;
  int n = 0;
  for (const auto& p : bed.pos)
    if (middle(p) && p.z > top - 0.5 * d0) sum += p.z, ++n;
  if (n == 0) throw RunError("CRM: the settled bed has no particles in the middle of the bin");
  return sum / n + 0.5 * d0;
}

namespace {
// The engine's arrays (sph_engine_impl.hpp): two soil states, the ids and four sort keys per
// particle; ten (twelve with wall normals) Vec4 per marker; two cell starts per cell, plus the CPU
// sort's counts.
double engine_bytes(const CrmMemoryNeed& n, std::size_t real, int records, bool normals, bool cpu) {
  const double per_particle = 2.0 * (4 + records) * 4 * double(real) + 5 * sizeof(int);
  const double per_marker = (normals ? 12 : 10) * 4 * double(real) + 4 * sizeof(int);
  const double per_cell = (cpu ? 3 : 2) * sizeof(int);
  return n.particles * per_particle + n.markers * per_marker + n.cells * per_cell;
}
}  // namespace

CrmMemoryNeed crm_memory_need(const CrmScene& sc, CrmDevice device) {
  CrmMemoryNeed n;
  const double d0 = sc.numerics.spacing;
  const CrmBin& bin = sc.bin;
  auto count = [&](double length) { return std::max(1.0, double(std::lround(length / d0))); };
  n.particles = count(bin.fill_length > 0 ? bin.fill_length : bin.size.x) * count(bin.size.y) * count(bin.fill_height);
  // The walls' and floor's marker layers around the bin, and each body's layers under its surface.
  const double L = bin.boundary_layers, mx = count(bin.size.x), my = count(bin.size.y);
  const double mz = std::max(1.0, std::ceil(bin.size.z / d0 - 1e-9));
  n.markers = (mx + 2 * L) * (my + 2 * L) * (mz + L) - mx * my * mz;
  for (const auto& b : sc.bodies) n.markers += 4 * M_PI * b.bounding_radius() * b.bounding_radius() / (d0 * d0) * L;
  try {
    n.cells = double(crm_grid(sc).cells());
  } catch (const InputError&) {
    n.cells = 2e9;  // crm_grid refuses more; the particles alone say by how much
  }
  int records = 0;
  sc.effects.named.for_each_named([&](auto tag) {
    using E = typename decltype(tag)::type;
    if constexpr (E::kRecord) ++records;
  });
  const bool normals = needs_wall_normals(sc.numerics.marker_velocity);
  const double host_soil = (4 + records) * sizeof(Vec4<double>) + sizeof(int);
  const double host_markers = (normals ? 4 : 3) * sizeof(Vec4<double>) + sizeof(Vec3<double>);
  n.host_bytes = 3 * n.particles * host_soil + n.markers * host_markers;
  if (device == CrmDevice::kCuda) {
    n.gpu_bytes = engine_bytes(n, sizeof(float), records, normals, false) + n.particles * 2 * sizeof(int);
  } else {
    const bool single = sc.numerics.cpu_precision == CrmPrecision::kFloat;
    n.host_bytes += engine_bytes(n, single ? sizeof(float) : sizeof(double), records, normals, true);
  }
  return n;
}

std::string CrmTerrain::description() const {
  const CrmScene& s = solver_.scene();
  return fmt::format("CRM, spacing {} m, step {:.3g} s", s.numerics.spacing, s.numerics.time_step);
}

std::string CrmTerrain::numerics_note() const {
  return density_cap_note(solver_.stats(), solver_.engine().soil_count());
}

void CrmTerrain::step() {
  solver_.step();
  // The wrenches every step (cheap); the soil's health every kCrmCheckEvery steps (crm_run_check.hpp).
  bool finite = true;
  for (const auto& w : solver_.wrenches())
    finite = finite && std::isfinite(w.force.x + w.force.y + w.force.z + w.torque.x + w.torque.y + w.torque.z);
  if (finite && solver_.steps() % kCrmCheckEvery == 0)
    if (const auto bad = health_.check(solver_)) throw RunError("CRM: " + bad->message);
  // A body that reaches the bin's floor was not carried by the soil: the spacing is too coarse for
  // it (particles leak past its markers) or its load is above the soil's bearing capacity.
  const CrmScene& sc = solver_.scene();
  for (std::size_t b = 0; b < sc.bodies.size(); ++b)
    if (solver_.bodies()[b].position.z < 0.5 * sc.numerics.spacing)
      throw RunError(fmt::format(
          "CRM: body '{}' reached the bin floor at t = {:.4g} s: the soil did not carry it (spacing {} m too "
          "coarse for the body, or its load above the bearing capacity)",
          sc.bodies[b].name, solver_.time(), sc.numerics.spacing));
  if (!finite)
    throw RunError(fmt::format("CRM: the state turned non-finite at step {} (t = {:.4g} s, step {:.3g} s)",
                               solver_.steps(), solver_.time(), solver_.time_step()));
}

CrmSite::CrmSite(const CrmScene& base, CrmDevice device, const std::filesystem::path& cache_dir)
    : base_(base), device_(device) {
  requested_step_ = base_.numerics.time_step;
  base_.bodies.clear();
  validate_crm_scene(base_);
  bed_ = settled_bed(base_, device_, cache_dir, &from_cache_);
  surface_ = bed_surface_height(bed_, base_);
}

std::string CrmSite::description() const {
  return fmt::format("CRM, spacing {} m, {} particles, bin {} x {} x {} m filled to {} m, surface at {:.4g} m",
                     base_.numerics.spacing, bed_.size(), base_.bin.size.x, base_.bin.size.y, base_.bin.size.z,
                     base_.bin.fill_height, surface_);
}

Vec3<double> CrmSite::centre() const {
  const double length = base_.bin.fill_length > 0 ? base_.bin.fill_length : base_.bin.size.x;
  return {0.5 * length, 0.5 * base_.bin.size.y, surface_};
}

double CrmSite::half_length() const {
  return 0.5 * (base_.bin.fill_length > 0 ? base_.bin.fill_length : base_.bin.size.x);
}

std::unique_ptr<Terrain> CrmSite::make(std::vector<RigidBody> bodies, double duration) const {
  CrmScene scene = base_;
  scene.bodies = std::move(bodies);
  scene.duration = duration;
  scene.numerics.time_step = requested_step_;
  validate_crm_scene(scene);
  return std::make_unique<CrmTerrain>(scene, device_, bed_);
}

}  // namespace terracal
