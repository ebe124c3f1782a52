#include "lowfi/scm_terrain.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "core/errors.hpp"

namespace terracal::lowfi {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kCoarseStride = 4;

// World-frame axis-aligned bounds of a body at a pose, from the 8 corners of its body-frame bounds.
void world_bounds(const ShapeRaycaster& shape, const BodyState& s, Vec3<double>& lo, Vec3<double>& hi) {
  const Vec3<double> a = shape.bounds_lo(), b = shape.bounds_hi();
  lo = {kInf, kInf, kInf};
  hi = {-kInf, -kInf, -kInf};
  for (int c = 0; c < 8; ++c) {
    const Vec3<double> corner{(c & 1) ? b.x : a.x, (c & 2) ? b.y : a.y, (c & 4) ? b.z : a.z};
    const Vec3<double> w = s.position + s.orientation.rotate(corner);
    for (int q = 0; q < 3; ++q) {
      lo[q] = std::min(lo[q], w[q]);
      hi[q] = std::max(hi[q], w[q]);
    }
  }
}
}  // namespace

ScmEffectChoice parse_scm_effects(const std::vector<std::string>& names, const std::string& key) {
  ScmEffectChoice e;
  e.named = effect_set_from_names<ScmEffects>(names, key);
  return e;
}

void validate(const ScmSettings& s, const ScmSoil& soil) {
  auto check = [](const char* key, double v, double lo, double hi, const char* unit) {
    if (!(v >= lo && v <= hi))
      throw InputError(fmt::format("SCM setting '{}' = {}: expected in [{}, {}] {}", key, v, lo, hi, unit));
  };
  check("grid", s.grid, 1e-4, 1.0, "m");
  check("time_step", s.time_step, 1e-6, 0.1, "s");
  check_effect_settings(s.effects, "SCM settings");
  if (!(norm(s.gravity) <= 1000))
    throw InputError(fmt::format("SCM setting 'gravity': |g| = {} outside [0, 1000] m/s^2", norm(s.gravity)));
  validate(soil, "SCM soil");
}

ScmTerrain::ScmTerrain(const ScmSoil& soil, const ScmSettings& settings, std::vector<RigidBody> bodies)
    : soil_(soil), settings_(settings), bodies_(std::move(bodies)), nodes_(settings.surface_height) {
  validate(settings_, soil_);
  tan_phi_ = std::tan(soil_.friction_deg * M_PI / 180.0);
  for (const auto& b : bodies_) {
    if (b.motion.any_free() && !(b.mass > 0))
      throw InputError(
          fmt::format("body '{}': mass = {}: a body with free degrees of freedom needs mass > 0", b.name, b.mass));
    shapes_.emplace_back(b.shape);
    BodyState s;
    s.position = b.position;
    s.orientation = b.orientation;
    s.velocity = b.motion.linear_at(0);
    s.omega = b.motion.angular_at(0);
    states_.push_back(s);
  }
  wrenches_.assign(bodies_.size(), {});
  update_contact();
  check_step();
}

std::string ScmTerrain::description() const {
  std::string effects;
  for (const std::string& e : effect_names(settings_.effects.named)) effects += " " + e;
  return fmt::format("SCM, grid {} m, step {} s, effects:{}", settings_.grid, settings_.time_step,
                     effects.empty() ? " none" : effects);
}

std::string ScmSite::description() const { return ScmTerrain(soil_, settings_, {}).description(); }

ScmTerrain::Volumes ScmTerrain::volumes() const {
  Volumes v;
  const double a = settings_.grid * settings_.grid;
  for (const auto& [k, n] : nodes_.nodes()) {
    v.pushed_down += n.plastic_sinkage * a;
    v.piled_up += n.level_offset * a;
  }
  return v;
}

const ScmNode* ScmTerrain::node(int i, int j) const { return nodes_.find(i, j); }

double ScmTerrain::free_surface(int i, int j) const { return nodes_.free_surface(i, j); }

// One vertical ray per node under each body's bounds, cast up from below the body to the highest
// the soil reaches. The body's outward normal at each hit comes from the hit heights of the
// neighbouring rays (central differences where both neighbours hit): shape-independent, and it
// lets the pressure act normal to the body as in Wong-Reece, so a wheel meets compaction resistance.
void ScmTerrain::cast_rays(std::vector<Hit>& hits) {
  hits.clear();
  const double top = settings_.surface_height + nodes_.max_level_offset();
  std::vector<RayGrid>& windows = scratch_.windows;
  windows.clear();
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    RayGrid r;
    if (!ray_grid(b, top, r)) continue;
    select_rays(b, r, top);
    cast_selected(b, r);
    add_hits(b, r, top, hits);
    windows.push_back(r);
  }
  // Bodies whose node windows are apart (a vehicle's wheels) cannot cover one node twice.
  bool overlap = false;
  for (std::size_t a = 0; a < windows.size() && !overlap; ++a)
    for (std::size_t c = a + 1; c < windows.size() && !overlap; ++c) {
      const RayGrid &p = windows[a], &q = windows[c];
      overlap = p.i0 < q.i0 + q.nx && q.i0 < p.i0 + p.nx && p.j0 < q.j0 + q.ny && q.j0 < p.j0 + p.ny;
    }
  if (overlap) {
    // Where two bodies cover a node, the lower one touches the soil.
    std::sort(hits.begin(), hits.end(), [](const Hit& a, const Hit& b) {
      return a.i != b.i ? a.i < b.i : a.j != b.j ? a.j < b.j : a.level < b.level;
    });
    hits.erase(
        std::unique(hits.begin(), hits.end(), [](const Hit& a, const Hit& b) { return a.i == b.i && a.j == b.j; }),
        hits.end());
  }
}

// The rays of the nodes under the body's bounds; false when there are none or the body is wholly
// above the soil.
bool ScmTerrain::ray_grid(std::size_t b, double top, RayGrid& r) const {
  const double g = settings_.grid;
  Vec3<double> lo, hi;
  world_bounds(shapes_[b], states_[b], lo, hi);
  if (lo.z >= top) return false;
  r.i0 = int(std::ceil(lo.x / g));
  r.j0 = int(std::ceil(lo.y / g));
  r.nx = int(std::floor(hi.x / g)) - r.i0 + 1;
  r.ny = int(std::floor(hi.y / g)) - r.j0 + 1;
  if (r.nx <= 0 || r.ny <= 0) return false;
  r.z0 = lo.z - 1e-6;
  r.t_max = top - r.z0 + 1e-6;
  // Ray in the body frame: origin R^T (o - c), direction R^T e_z.
  const Quat& q = states_[b].orientation;
  const Quat inv{q.w, -q.x, -q.y, -q.z};
  r.dir = shapes_[b].direction(inv.rotate({0, 0, 1}));
  r.o00 = inv.rotate(Vec3<double>{r.i0 * g, r.j0 * g, r.z0} - states_[b].position);
  r.step_i = inv.rotate({g, 0, 0});
  r.step_j = inv.rotate({0, g, 0});
  return true;
}

// Most of a body's bounds is far above the soil (a wheel touches it over a fifth of its length).
// A coarse pass every kCoarseStride nodes finds where the underside comes within `margin` of the
// highest soil; only the nodes within one coarse cell of those are wanted. The margin covers how
// far the underside can dip between coarse nodes (ShapeRaycaster::dip_over) plus the grousers'
// height, so no contact between coarse nodes is missed. Meshes (which may have thin spikes) and
// rings narrower than two coarse cells want every node (scratch_.wanted left empty).
void ScmTerrain::select_rays(std::size_t b, const RayGrid& r, double top) {
  const ShapeRaycaster& shape = shapes_[b];
  const double g = settings_.grid;
  const int stride = kCoarseStride, nx = r.nx, ny = r.ny;
  std::vector<char>& wanted = scratch_.wanted;
  wanted.clear();
  if (!(settings_.coarse_rays && shape.smooth_underside() && nx * ny >= 16 * stride * stride &&
        shape.narrowest() >= 2 * stride * g))
    return;
  const int cx = (nx - 1) / stride + 2, cy = (ny - 1) / stride + 2;  // coarse nodes, the last at or past the edge
  const double margin = shape.dip_over(stride * g) + shape.feature_depth() + 1e-9;
  std::vector<char>& near = scratch_.near;
  near.assign(std::size_t(cx) * cy, 0);
  for (int b2 = 0; b2 < cy; ++b2)
    for (int a2 = 0; a2 < cx; ++a2) {
      const int ii = std::min(a2 * stride, nx - 1), jj = std::min(b2 * stride, ny - 1);
      const double t = shape.first_hit(r.dir, r.row(jj) + double(ii) * r.step_i, r.t_max + margin);
      near[std::size_t(b2) * cx + a2] = r.z0 + t < top + margin;
    }
  wanted.assign(std::size_t(nx) * ny, 0);
  for (int b2 = 0; b2 < cy; ++b2)
    for (int a2 = 0; a2 < cx; ++a2) {
      if (!near[std::size_t(b2) * cx + a2]) continue;
      const int ilo = std::max(0, (a2 - 1) * stride), ihi = std::min(nx - 1, (a2 + 1) * stride);
      const int jlo = std::max(0, (b2 - 1) * stride), jhi = std::min(ny - 1, (b2 + 1) * stride);
      for (int jj = jlo; jj <= jhi; ++jj)
        std::fill(wanted.begin() + std::size_t(jj) * nx + ilo, wanted.begin() + std::size_t(jj) * nx + ihi + 1, 1);
    }
}

// scratch_.level: the underside's height over each wanted node (+infinity where the ray misses or
// the node is not wanted). Runs of wanted nodes along a row are cast together (first_hits).
void ScmTerrain::cast_selected(std::size_t b, const RayGrid& r) {
  const int nx = r.nx, ny = r.ny;
  std::vector<double>& level = scratch_.level;
  level.assign(std::size_t(nx) * ny, kInf);
  const std::vector<char>& wanted = scratch_.wanted;
#pragma omp parallel for schedule(static) if (nx * ny > 20000)
  for (int jj = 0; jj < ny; ++jj) {
    double* row = level.data() + std::size_t(jj) * nx;
    const char* want = wanted.empty() ? nullptr : wanted.data() + std::size_t(jj) * nx;
    for (int ii = 0, end = 0; ii < nx; ii = end) {
      while (want && ii < nx && !want[ii]) ++ii;
      for (end = ii; end < nx && (!want || want[end]);) ++end;  // the run [ii, end)
      shapes_[b].first_hits(r.dir, r.row(jj), r.step_i, ii, end, r.t_max, row);
      for (int k = ii; k < end; ++k) row[k] += r.z0;  // parameter to height (a miss stays +infinity)
    }
  }
}

// The nodes whose ray hit below the highest soil, with the body's normal there from the heights
// of the neighbouring rays.
void ScmTerrain::add_hits(std::size_t b, const RayGrid& r, double top, std::vector<Hit>& hits) const {
  const double g = settings_.grid;
  const int nx = r.nx, ny = r.ny;
  const std::vector<double>& level = scratch_.level;
  auto at = [&](int ii, int jj) {
    return (ii < 0 || jj < 0 || ii >= nx || jj >= ny) ? kInf : level[std::size_t(jj) * nx + ii];
  };
  auto slope = [&](double minus, double here, double plus) {
    if (minus < kInf && plus < kInf) return (plus - minus) / (2 * g);
    if (plus < kInf) return (plus - here) / g;
    if (minus < kInf) return (here - minus) / g;
    return 0.0;
  };
  for (int jj = 0; jj < ny; ++jj)
    for (int ii = 0; ii < nx; ++ii) {
      const double h = at(ii, jj);
      if (!(h < top)) continue;  // no hit, or above any soil; contact() checks against this node's surface
      // The underside z = h(x, y): outward (downward-facing) normal is (dh/dx, dh/dy, -1); the soil
      // pushes along minus that, i.e. along (-dh/dx, -dh/dy, 1).
      const double hx = slope(at(ii - 1, jj), h, at(ii + 1, jj)), hy = slope(at(ii, jj - 1), h, at(ii, jj + 1));
      const double inv_len = 1.0 / std::sqrt(1 + hx * hx + hy * hy);
      hits.push_back({r.i0 + ii, r.j0 + jj, int(b), h, {-hx * inv_len, -hy * inv_len, inv_len}});
    }
}

// The pressure and shear of the nodes the bodies push into, and the wrenches they put on the bodies.
void ScmTerrain::contact(const std::vector<Hit>& candidates) {
  for (auto& w : wrenches_) w = {};
  stats_ = {};
  stats_.body_contact_area.assign(bodies_.size(), 0.0);
  stats_.body_max_sinkage.assign(bodies_.size(), 0.0);
  select_pressed(candidates);
  const std::vector<Hit>& hits = scratch_.pressed;
  stats_.rays = int(hits.size());
  // Contact patches and their Bekker widths.
  ContactPatches& patches = scratch_.patches;
  find_contact_patches(scratch_.pressed_at, settings_.grid, patches);
  stats_.patches = int(patches.count());
  stats_.patch_bekker_width = patches.bekker_width;
  check_bekker_strength(hits, patches);
  std::vector<double>& displaced = scratch_.displaced;
  displaced.assign(patches.count(), 0.0);
  for (std::size_t h = 0; h < hits.size(); ++h) {
    const int p = patches.patch_of[h];
    press(hits[h], *scratch_.pressed_nodes[h], patches.bekker_width[p], displaced[p]);
  }
  release_left_nodes();
  ScmContactView view{scratch_.pressed_at, patches, displaced, nodes_, settings_.grid};
  settings_.effects.named.for_each_named([&](auto tag) {
    using E = typename decltype(tag)::type;
    E::after_contact(settings_.effects.of<E>(), view);
  });
}

// The hits below their node's free surface, each with its node: one hash lookup per hit, and a
// node is stored only once a body has pushed into it.
void ScmTerrain::select_pressed(const std::vector<Hit>& candidates) {
  std::vector<Hit>& hits = scratch_.pressed;
  std::vector<ScmNode*>& nodes = scratch_.pressed_nodes;
  std::vector<GridIndex>& at = scratch_.pressed_at;
  hits.clear();
  nodes.clear();
  at.clear();
  for (const Hit& c : candidates) {
    const ScmNodeGrid::Key k = ScmNodeGrid::key(c.i, c.j);
    auto it = nodes_.find(k);
    const double surface =
        settings_.surface_height + (it == nodes_.end() ? 0.0 : it->second.level_offset - it->second.plastic_sinkage);
    if (c.level >= surface) continue;
    if (it == nodes_.end()) it = nodes_.emplace(k);
    hits.push_back(c);
    nodes.push_back(&it->second);
    at.push_back({c.i, c.j});
  }
}

// Refuses a patch whose Bekker width leaves the pressure-sinkage law without strength, naming the
// body of its first node. Patches are numbered in order of their first node, so the first failing
// patch holds the first failing node.
void ScmTerrain::check_bekker_strength(const std::vector<Hit>& hits, const ContactPatches& patches) const {
  for (std::size_t p = 0; p < patches.count(); ++p) {
    const double b = patches.bekker_width[p];
    if (soil_.Kc / b + soil_.Kphi > 0) continue;
    const auto h = std::find(patches.patch_of.begin(), patches.patch_of.end(), int(p)) - patches.patch_of.begin();
    throw NoBekkerStrength(fmt::format(
        "SCM: body '{}' at t = {:.4g} s: contact patch of Bekker width b = {:.3g} m gives Kc/b + Kphi = {:.4g} "
        "Pa/m^n <= 0: this set's pressure-sinkage law has no strength for contacts narrower than "
        "|Kc|/Kphi = {:.3g} m (calibrate on plates nearer this width, or fix Kc)",
        bodies_[hits[h].body].name, time_, b, soil_.Kc / b + soil_.Kphi, std::abs(soil_.Kc) / soil_.Kphi));
  }
}

// One node under a body: elastic-plastic pressure, damping and Janosi shear, and their force and
// torque on the body. displaced: the patch's plastic volume pushed aside this step.
void ScmTerrain::press(const Hit& hit, ScmNode& n, double b, double& displaced) {
  const double g = settings_.grid, area = g * g, dt = settings_.time_step;
  const double ke = soil_.elastic_stiffness;
  const double undisturbed = settings_.surface_height + n.level_offset;
  const double z = undisturbed - hit.level;  // total sinkage
  const BodyState& s = states_[hit.body];
  const Vec3<double> p{hit.i * g, hit.j * g, hit.level};
  const Vec3<double> r = p - s.position;
  const Vec3<double> v = s.velocity + cross(s.omega, r);
  const Vec3<double> nrm = hit.normal;
  // Elastic trial, capped at the Bekker yield (or an effect's); yielding moves the plastic sinkage down.
  double sigma = ke * (z - n.plastic_sinkage);
  double yield = soil_.bekker_pressure(z, b);
  settings_.effects.named.for_each_named([&](auto tag) {
    using E = typename decltype(tag)::type;
    E::yield(settings_.effects.of<E>(), soil_, v, s.velocity, nrm, z, b, yield);
  });
  if (sigma > yield) {
    const double zp = z - yield / ke;
    displaced += (zp - n.plastic_sinkage) * area;
    n.plastic_sinkage = zp;
    sigma = yield;
  }
  settings_.effects.named.for_each_named([&](auto tag) {
    using E = typename decltype(tag)::type;
    E::pressure(settings_.effects.of<E>(), soil_, v, nrm, sigma);
  });
  sigma = std::max(sigma, 0.0);
  // Janosi shear from the displacement accumulated along the body's surface during this contact.
  const Vec3<double> v_tan = v - dot(v, nrm) * nrm;
  n.shear += dt * v_tan;
  n.shear -= dot(n.shear, nrm) * nrm;  // keep it in the current tangent plane
  const double j = norm(n.shear);
  const double tau = j > 0 ? (soil_.cohesion + sigma * tan_phi_) * (1.0 - std::exp(-j / soil_.janosi_k)) : 0.0;
  n.sigma = sigma;
  n.tau = tau;
  n.last_sinkage = z;
  n.in_contact = true;
  n.contact_step = steps_;
  // Pressure on the body's surface element (projected area g^2, true area g^2 / n_z).
  const double surface = area / nrm.z;
  Vec3<double> f = (sigma * surface) * nrm;
  if (j > 0) f -= (tau * surface / j) * n.shear;
  BodyWrench& w = wrenches_[hit.body];
  w.force += f;
  w.torque += cross(r, f);
  ++stats_.contact_nodes;
  stats_.contact_area += area;
  stats_.body_contact_area[hit.body] += area;
  stats_.max_sinkage = std::max(stats_.max_sinkage, z);
  stats_.body_max_sinkage[hit.body] = std::max(stats_.body_max_sinkage[hit.body], z);
}

// Nodes the bodies left this step: the shear spring is released; without elastic unloading the
// soil stays where the body last held it (header: why, and why not the deepest sinkage). The nodes pressed
// this step are the next step's contact nodes.
void ScmTerrain::release_left_nodes() {
  for (ScmNode* node : contact_nodes_) {
    ScmNode& n = *node;
    if (n.contact_step == steps_) continue;                    // still in contact
    double rut = std::max(n.plastic_sinkage, n.last_sinkage);  // the effects may keep another (elastic_unloading)
    settings_.effects.named.for_each_named([&](auto tag) {
      using E = typename decltype(tag)::type;
      E::release(settings_.effects.of<E>(), n, rut);
    });
    n.plastic_sinkage = rut;
    n.last_sinkage = 0;
    n.shear = {};
    n.sigma = n.tau = 0;
    n.in_contact = false;
  }
  contact_nodes_.swap(scratch_.pressed_nodes);
}

// A free body resting on the elastic soil is a mass on a spring of stiffness Ke x contact area;
// symplectic Euler is stable only while omega dt < 2. Past that the body bounces ever higher, so say
// so (and by how much) instead of returning nonsense.
void ScmTerrain::check_step() const {
  const double dt = settings_.time_step;
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    if (!bodies_[b].motion.free[2]) continue;
    const double k = soil_.elastic_stiffness * stats_.body_contact_area[b];
    const double omega = std::sqrt(k / bodies_[b].mass);
    if (omega * dt >= 2.0)
      throw RunError(fmt::format(
          "SCM: body '{}' at t = {:.4g} s: time step {} s is unstable for its contact (elastic stiffness {} Pa/m "
          "x contact area {:.4g} m^2 on mass {} kg: omega dt = {:.3g} >= 2); use a step below {:.3g} s",
          bodies_[b].name, time_, dt, soil_.elastic_stiffness, stats_.body_contact_area[b], bodies_[b].mass, omega * dt,
          2.0 / omega));
  }
}

// Symplectic Euler: velocities from the wrench at the current pose, then the pose from the new
// velocities (stable for the stiff elastic contact where explicit Euler would gain energy). The
// contact is then evaluated at the new pose, so that bodies() and wrenches() always belong together.
void ScmTerrain::step() {
  const double dt = settings_.time_step;
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    const BodyState& s = states_[b];
    BodyState next = advance_body(bodies_[b], s, s, wrenches_[b], settings_.gravity, dt, time_ + dt);
    next.position = s.position + dt * next.velocity;
    next.orientation = integrate_rotation(s.orientation, next.omega, dt);
    states_[b] = next;
  }
  time_ += dt;
  ++steps_;
  update_contact();
  check_step();
}

void ScmTerrain::step_at(const std::vector<BodyState>& states) {
  if (states.size() != bodies_.size())
    throw RunError(
        fmt::format("SCM at t = {:.4g} s: {} body states given for {} bodies", time_, states.size(), bodies_.size()));
  // The ray windows index grid nodes by int: a body must stay well inside that range.
  const double reach = settings_.grid * double(1 << 30);
  for (std::size_t b = 0; b < states.size(); ++b) {
    const BodyState& s = states[b];
    auto fail = [&](const std::string& why) {
      throw RunError(fmt::format("SCM: body '{}' at t = {:.4g} s: {}", bodies_[b].name, time_, why));
    };
    auto finite = [](const Vec3<double>& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
    const Quat& q = s.orientation;
    const double qn = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    if (!finite(s.position))
      fail(fmt::format("position ({}, {}, {}) is not finite", s.position.x, s.position.y, s.position.z));
    if (!(std::isfinite(qn) && qn > 1e-12))
      fail(fmt::format("orientation ({}, {}, {}, {}) is not a rotation (non-finite or zero quaternion)", q.w, q.x, q.y,
                       q.z));
    if (!finite(s.velocity))
      fail(fmt::format("velocity ({}, {}, {}) is not finite", s.velocity.x, s.velocity.y, s.velocity.z));
    if (!finite(s.omega))
      fail(fmt::format("angular velocity ({}, {}, {}) is not finite", s.omega.x, s.omega.y, s.omega.z));
    const double r = bodies_[b].bounding_radius();
    if (!(std::abs(s.position.x) + r < reach && std::abs(s.position.y) + r < reach))
      fail(fmt::format("position ({}, {}) m is beyond the grid's range (|x|, |y| < {:.3g} m at grid {} m)",
                       s.position.x, s.position.y, reach, settings_.grid));
  }
  for (std::size_t b = 0; b < states.size(); ++b) {
    states_[b] = states[b];
    const Quat& q = states[b].orientation;
    // A unit quaternion is kept as it is, bit for bit (the same rays as the terrain's own step()).
    if (std::abs(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z - 1) > 1e-14) states_[b].orientation = q.normalized();
  }
  time_ += settings_.time_step;
  ++steps_;
  update_contact();
}

void ScmTerrain::update_contact() {
  cast_rays(scratch_.hits);
  contact(scratch_.hits);
}

}  // namespace terracal::lowfi
