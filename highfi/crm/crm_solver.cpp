#include "highfi/crm/crm_solver.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "core/rng.hpp"
#include "highfi/crm/body_markers.hpp"

namespace terracal {

SphConstants<double> crm_constants(const CrmScene& sc) {
  SphConstants<double> k;
  const CrmSoil& s = sc.soil;
  const CrmNumerics& n = sc.numerics;
  k.kernel = SphKernel<double>::make(n.kernel, n.smoothing_length());
  k.model.shear_modulus = s.shear_modulus();
  k.model.bulk_modulus = s.bulk_modulus();
  k.model.mu_s = s.mu_s;
  k.model.mu_2 = s.mu_2;
  k.model.I0 = s.I0;
  k.model.grain_diameter = s.grain_diameter;
  k.model.rho0 = s.density;
  k.model.cohesion = 0;  // unless an effect sets it (cohesion)
  sc.effects.named.for_each_named([&](auto tag) {
    using E = typename decltype(tag)::type;
    E::soil_model(sc.effects.of<E>(), s, k.model);
  });
  k.mass = s.density * n.spacing * n.spacing * n.spacing;
  k.gravity = s.gravity;
  k.free_surface_support = n.free_surface_support;
  k.spacing = n.spacing;
  k.marker_velocity = n.marker_velocity;
  k.wall_contact = n.wall_contact;
  k.wall_contact_inv_reach = 1.0 / n.spacing;
  return k;
}

GridGeometry<double> crm_grid(const CrmScene& sc) {
  // The domain: the bin with its wall layers, one support radius around it, and headroom above the
  // walls and the bodies. Particles that leave it are lost (reported, never a crash).
  const double d0 = sc.numerics.spacing, h = sc.numerics.smoothing_length();
  const int reach = sc.numerics.grid_reach;
  // With a sort skin the cells are wider by the skin, so that the particles may move 2 h skin out of
  // their cells before the next sort (EngineSetup::sort_drift).
  const double cell = 2 * h * (1 + sc.numerics.sort_skin) / reach;
  const double pad = sc.bin.boundary_layers * d0 + 2 * h;
  double top = std::max(sc.bin.size.z, sc.bin.fill_height) + 0.25 * sc.bin.size.z;
  for (const auto& b : sc.bodies) top = std::max(top, b.position.z + b.bounding_radius() + 2 * h);
  GridGeometry<double> g;
  g.origin = {-pad, -pad, -pad};
  g.inv_cell = 1.0 / cell;
  g.reach = reach;
  g.nx = int(std::ceil((sc.bin.size.x + 2 * pad) / cell));
  g.ny = int(std::ceil((sc.bin.size.y + 2 * pad) / cell));
  g.nz = int(std::ceil((top + pad) / cell));
  if (double(g.nx) * g.ny * g.nz > 2e9)
    throw InputError("the neighbour grid would exceed 2e9 cells: the bin is too large for this spacing");
  return g;
}

HostSoil initial_bed(const CrmScene& sc) {
  const double d0 = sc.numerics.spacing;
  const int nx = int(std::lround((sc.bin.fill_length > 0 ? sc.bin.fill_length : sc.bin.size.x) / d0));
  const int ny = int(std::lround(sc.bin.size.y / d0));
  const int nz = int(std::lround(sc.bin.fill_height / d0));
  const double H = nz * d0, rho = sc.soil.density, g = std::abs(sc.soil.gravity.z);
  const double k0 = sc.soil.poisson_ratio / (1 - sc.soil.poisson_ratio);
  HostSoil s;
  const std::size_t n = std::size_t(nx) * ny * nz;
  s.pos.reserve(n);
  s.vel.reserve(n);
  s.s0.reserve(n);
  s.s1.reserve(n);
  s.ids.reserve(n);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const double z = (k + 0.5) * d0;
        const double szz = -rho * g * (H - z);
        s.pos.push_back({(i + 0.5) * d0, (j + 0.5) * d0, z, rho});
        s.vel.push_back({0, 0, 0, double(kParticleActive)});
        s.s0.push_back({k0 * szz, k0 * szz, szz, 0});
        s.s1.push_back({0, 0, 0, 1});
        s.ids.push_back(int(s.ids.size()));
      }
  return s;
}

void jitter_positions(HostSoil& soil, double amplitude, std::uint64_t seed) {
  if (!(amplitude > 0)) return;
  Rng rng(seed);
  auto offset = [&] { return amplitude * (2 * rng.uniform() - 1); };
  for (auto& p : soil.pos) {
    p.x += offset();
    p.y += offset();
    p.z += offset();
  }
}

HostSoil settling_start(const CrmScene& scene) {
  HostSoil soil = initial_bed(scene);
  jitter_positions(soil, scene.settle_jitter * scene.numerics.spacing, std::uint64_t(scene.settle_seed));
  return soil;
}

CrmSolver::CrmSolver(const CrmScene& scene, CrmDevice device, const HostSoil* bed) : scene_(scene) {
  const double d0 = scene_.numerics.spacing;
  EngineSetup setup;
  setup.constants = crm_constants(scene_);
  setup.grid = crm_grid(scene_);
  // A little under the cells' 2 h skin of slack, for the round-off of the float32 cell arithmetic.
  setup.sort_drift = 0.999 * 2 * scene_.numerics.smoothing_length() * scene_.numerics.sort_skin;
  {
    const double half = 0.5 * scene_.numerics.spacing;
    setup.room_lo = {-half, -half, -half};
    setup.room_hi = {scene_.bin.size.x + half, scene_.bin.size.y + half, 1e30};
  }
  setup.soil = bed ? *bed : initial_bed(scene_);
  setup.effects = scene_.effects.named;
  setup.effect_constants_double = crm_effect_constants<double>(scene_);
  setup.effect_constants_float = crm_effect_constants<float>(scene_);
  setup.bodies = int(scene_.bodies.size()) + 1;
  const double rho = scene_.soil.density;
  const bool with_normals = needs_wall_normals(scene_.numerics.marker_velocity);
  for (const auto& p : bin_marker_positions(scene_.bin, d0)) {
    setup.markers.pos.push_back({p.x, p.y, p.z, rho});
    setup.markers.local.push_back({p.x, p.y, p.z, 0.0});
    setup.markers.wall_vel.push_back({0, 0, 0, 0});
    if (with_normals) setup.markers.normal.push_back(bin_marker_normal(scene_.bin, p));
  }
  for (std::size_t b = 0; b < scene_.bodies.size(); ++b) {
    const CrmBody& body = scene_.bodies[b];
    body_local_.push_back(body_marker_positions(body.shape, d0, scene_.bin.boundary_layers));
    BodyState st{body.position, body.orientation, body.motion.linear_velocity, body.motion.angular_velocity};
    bodies_.push_back(st);
    for (const auto& l : body_local_.back()) {
      const Vec3<double> r = body.orientation.rotate(l);
      const Vec3<double> x = body.position + r, v = st.velocity + cross(st.omega, r);
      setup.markers.pos.push_back({x.x, x.y, x.z, rho});
      setup.markers.local.push_back({l.x, l.y, l.z, double(b + 1)});
      setup.markers.wall_vel.push_back({v.x, v.y, v.z, body.motion.moves() ? 1.0 : 0.0});
      if (with_normals) setup.markers.normal.push_back(body_marker_normal(body.shape, l, d0));
    }
  }
  wrenches_.assign(scene_.bodies.size(), {});
  engine_ =
      device == CrmDevice::kCuda ? make_cuda_engine(setup) : make_cpu_engine(setup, scene_.numerics.cpu_precision);
  engine_->set_poses(poses(bodies_));
  engine_->set_active({});  // every particle, until an effect focuses the step (active_domain)
}

HostSoil CrmSolver::soil() const {
  HostSoil s;
  engine_->download(s);
  return s;
}

void CrmSolver::restore(const HostSoil& soil, const std::vector<BodyState>& bodies, double time, long steps) {
  if (bodies.size() != bodies_.size()) throw RunError("checkpoint: the number of bodies differs from the scene");
  engine_->upload(soil);
  bodies_ = bodies;
  time_ = time;
  steps_ = steps;
  engine_->set_poses(poses(bodies_));
}

std::vector<BodyPose<double>> CrmSolver::poses(const std::vector<BodyState>& states) const {
  std::vector<BodyPose<double>> p(states.size() + 1);  // 0: the bin's walls, at rest
  for (std::size_t b = 0; b < states.size(); ++b) {
    BodyPose<double>& q = p[b + 1];
    q.center = states[b].position;
    q.velocity = states[b].velocity;
    q.omega = states[b].omega;
    states[b].orientation.to_matrix(q.R);
    q.moving = scene_.bodies[b].motion.moves() ? 1 : 0;
  }
  return p;
}

// One midpoint step of soil and bodies: the soil's stage A -> B over dt/2 with the bodies at their
// poses, the bodies' half step under the soil's wrench, then the soil's stage B -> A over dt with
// the bodies at their half-step poses and the bodies' full step. Prescribed velocities take their
// value at the time each update ends (advance_body).
void CrmSolver::step() {
  const double dt = scene_.numerics.time_step;
  CrmStepView view{scene_.bodies, bodies_, *engine_};
  scene_.effects.named.for_each_named([&](auto tag) {
    using E = typename decltype(tag)::type;
    E::before_step(scene_.effects.of<E>(), view);
  });
  engine_->begin_step();
  const std::size_t nb = bodies_.size();
  auto unpack = [&](const std::vector<double>& w, std::size_t b) {
    const double* p = w.data() + 6 * b;
    return BodyWrench{{p[0], p[1], p[2]}, {p[3], p[4], p[5]}};
  };
  engine_->set_poses(poses(bodies_));
  // The half step's wrench moves only free bodies: with none, the device need not be waited for.
  const bool any_free = std::any_of(scene_.bodies.begin(), scene_.bodies.end(),
                                    [](const CrmBody& b) { return b.motion.any_free(); });
  const std::vector<double> w0 = engine_->stage(0, dt, any_free);
  std::vector<BodyState> half(nb);
  for (std::size_t b = 0; b < nb; ++b)
    half[b] = advance_body(scene_.bodies[b], bodies_[b], bodies_[b], unpack(w0, b + 1), scene_.soil.gravity, 0.5 * dt,
                           time_ + 0.5 * dt);
  engine_->set_poses(poses(half));
  const std::vector<double> w1 = engine_->stage(1, dt, true);
  for (std::size_t b = 0; b < nb; ++b) {
    wrenches_[b] = unpack(w1, b + 1);
    work_on_soil_ -= dt * (dot(wrenches_[b].force, half[b].velocity) + dot(wrenches_[b].torque, half[b].omega));
    bodies_[b] = advance_body(scene_.bodies[b], bodies_[b], half[b], wrenches_[b], scene_.soil.gravity, dt, time_ + dt);
  }
  wall_wrench_ = unpack(w1, 0);
  time_ += dt;
  ++steps_;
}

}  // namespace terracal
