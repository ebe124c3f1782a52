#include "highfi/crm/crm_run_check.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>

namespace terracal {

double soil_mechanical_energy(const SoilStats& st, const Vec3<double>& gravity) {
  return st.kinetic_energy - dot(gravity, st.first_moment);
}

namespace {

// Where a point is: on (or near) a body, at a wall of the bin, outside the bin, or in the soil.
std::string place_of(const Vec3<double>& x, const CrmSolver& solver) {
  const CrmScene& sc = solver.scene();
  const double reach = 2 * sc.numerics.smoothing_length();
  const Vec3<double>& size = sc.bin.size;
  if (x.z < 0) return "below the bin's floor";
  if (x.x < 0 || x.y < 0 || x.x > size.x || x.y > size.y)
    return x.z > size.z ? "thrown over the bin's walls" : "through a wall of the bin";
  if (x.z > 1.25 * size.z) return "thrown out of the top of the domain";
  for (std::size_t b = 0; b < sc.bodies.size(); ++b) {
    const Vec3<double> d = x - solver.bodies()[b].position;
    if (std::sqrt(dot(d, d)) < sc.bodies[b].bounding_radius() + reach)
      return fmt::format("at body '{}' (centre [{:.4g}, {:.4g}, {:.4g}] m)", sc.bodies[b].name,
                         solver.bodies()[b].position.x, solver.bodies()[b].position.y, solver.bodies()[b].position.z);
  }
  if (x.x < reach || x.y < reach || x.x > size.x - reach || x.y > size.y - reach || x.z < reach)
    return "at a wall of the bin";
  return "in the soil, away from bodies and walls";
}

// The particles a failure is about, found in a copy of the soil: the fastest, the lost or the
// non-finite ones. Returns "N particles around [x, y, z] m, <place>" for their centroid.
std::string where(const CrmSolver& solver, const std::string& kind) {
  const HostSoil soil = solver.soil();
  std::vector<std::size_t> pick;
  for (std::size_t i = 0; i < soil.size(); ++i) {
    const auto& v = soil.vel[i];
    const bool finite = std::isfinite(v.x + v.y + v.z + soil.pos[i].x + soil.pos[i].y + soil.pos[i].z);
    if (kind == "non-finite" ? !finite : kind == "lost" ? v.w == double(kParticleLost) : finite) pick.push_back(i);
  }
  if (kind == "too fast" || kind == "energy") {  // the fastest: at least half the top speed
    auto speed2 = [&](std::size_t i) {
      const auto& v = soil.vel[i];
      return v.w == double(kParticleLost) ? -1.0 : v.x * v.x + v.y * v.y + v.z * v.z;
    };
    double top = 0;
    for (std::size_t i : pick) top = std::max(top, speed2(i));
    std::erase_if(pick, [&](std::size_t i) { return speed2(i) < 0.25 * top; });
  }
  Vec3<double> c{}, lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  std::size_t used = 0;
  for (std::size_t i : pick) {
    const Vec3<double> p{soil.pos[i].x, soil.pos[i].y, soil.pos[i].z};
    if (!std::isfinite(p.x + p.y + p.z)) continue;
    c += p;
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    ++used;
  }
  if (used == 0) return fmt::format("{} particles, their positions non-finite", pick.size());
  c = (1.0 / double(used)) * c;
  if (used == 1) return fmt::format("1 particle at [{:.4g}, {:.4g}, {:.4g}] m, {}", c.x, c.y, c.z, place_of(c, solver));
  // Several: their centroid (and its place), and the box they spread over.
  return fmt::format(
      "{} particles around [{:.4g}, {:.4g}, {:.4g}] m (within [{:.4g}, {:.4g}] x [{:.4g}, {:.4g}] x [{:.4g}, {:.4g}] "
      "m), "
      "{}",
      pick.size(), c.x, c.y, c.z, lo.x, hi.x, lo.y, hi.y, lo.z, hi.z, place_of(c, solver));
}

}  // namespace

std::string density_cap_note(const SoilStats& st, std::size_t particles) {
  const long active = long(particles) - st.frozen - st.lost - st.nonfinite;
  if (st.at_density_cap == 0 || active <= 0) return {};
  return fmt::format("{} of {} active particles ({:.3g} %) held at the density cap", st.at_density_cap, active,
                     100.0 * double(st.at_density_cap) / double(active));
}

CrmRunCheck::CrmRunCheck(const CrmSolver& solver) {
  const SoilStats st = solver.stats();
  const CrmScene& sc = solver.scene();
  lost0_ = st.lost;
  energy0_ = soil_mechanical_energy(st, sc.soil.gravity);
  work0_ = solver.work_on_soil();
  speed_limit_ = sc.soil.sound_speed() + 2 * sc.numerics.expected_speed;
  // A margin for energy the soil may release without a source: twice its kinetic energy now, and
  // the bed's weight over one spacing (elastic energy it gives back, compaction).
  slack_ = st.kinetic_energy + st.mass * std::sqrt(dot(sc.soil.gravity, sc.soil.gravity)) * sc.numerics.spacing;
}

std::optional<CrmFailure> CrmRunCheck::check(const CrmSolver& solver) const {
  const SoilStats st = solver.stats();
  const CrmScene& sc = solver.scene();
  const std::string at =
      fmt::format("at t = {:.6g} s (step {}, dt = {:.4g} s)", solver.time(), solver.steps(), solver.time_step());
  auto fail = [&](const char* kind, const std::string& what, const std::string& hint) {
    return CrmFailure{kind, fmt::format("{} {}: {}; {}", what, at, where(solver, kind), hint)};
  };
  const std::string step_hint = fmt::format(
      "try a smaller step (resolution.cfl, now {:.3g}, or resolution.time_step) or a finer spacing (now {} m)",
      sc.numerics.cfl, sc.numerics.spacing);
  if (st.nonfinite > 0)
    return fail("non-finite", fmt::format("{} particles have a non-finite state", st.nonfinite), step_hint);
  const double n = double(solver.engine().soil_count());
  const long lost = st.lost - lost0_;
  if (double(lost) > sc.checks.max_lost_fraction * n)
    return fail("lost",
                fmt::format("{} particles ({:.3g} %) left the soil's room, above checks.max_lost_fraction = {:.3g} %",
                            lost, 100 * double(lost) / n, 100 * sc.checks.max_lost_fraction),
                "particles that leave through a wall were pushed through its markers (a finer spacing, "
                "more resolution.h_over_d0 or boundary layers); thrown out of the top, the soil blew up (" +
                    step_hint + ")");
  if (st.max_speed > speed_limit_)
    return fail(
        "too fast",
        fmt::format("a particle moves at {:.3g} m/s, above c_s + 2 v_max = {:.3g} m/s (c_s = {:.3g} m/s, "
                    "v_max = {:.3g} m/s, the bodies' largest speed or a fall over the wall height): the soil is "
                    "blowing up",
                    st.max_speed, speed_limit_, sc.soil.sound_speed(), sc.numerics.expected_speed),
        step_hint);
  const double gained = soil_mechanical_energy(st, sc.soil.gravity) - energy0_;
  const double work = solver.work_on_soil() - work0_;
  if (gained > std::max(work, 0.0) + slack_ + 0.1 * std::abs(work))
    return fail("energy",
                fmt::format("the soil's kinetic plus potential energy grew by {:.4g} J, more than the bodies' work "
                            "on it ({:.4g} J) can supply",
                            gained, work),
                step_hint);
  return std::nullopt;
}

}  // namespace terracal
