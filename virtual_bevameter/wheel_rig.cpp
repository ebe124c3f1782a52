#include "virtual_bevameter/wheel_rig.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "core/json_file.hpp"
#include "core/json_object.hpp"
#include "virtual_bevameter/rig_checks.hpp"

namespace terracal::rigs {

void validate(const WheelSpec& w) {
  check_range("wheel radius", w.radius, 0.01, 10, "m");
  check_range("wheel width", w.width, 0.005, 10, "m");
  check_range("wheel mass", w.mass, 1e-3, 1e6, "kg");
  check_range("wheel angular_velocity", w.angular_velocity, 0, 100, "rad/s");
  check_range("wheel grousers.count", w.grouser_count, 0, 360, "");
  check_range("wheel grousers.height", w.grouser_height, 0, 0.5 * w.radius, "m (at most half the radius)");
  check_range("wheel grousers.thickness", w.grouser_thickness, 0, w.radius, "m");
  if (w.grouser_count > 0 && !(w.grouser_height > 0 && w.grouser_thickness > 0))
    throw InputError(fmt::format("wheel grousers: count = {} needs height > 0 and thickness > 0 (got {}, {})",
                                 w.grouser_count, w.grouser_height, w.grouser_thickness));
}

nlohmann::json wheel_json(const WheelSpec& w) {
  return {{"radius", w.radius},
          {"width", w.width},
          {"mass", w.mass},
          {"angular_velocity", w.angular_velocity},
          {"grousers", {{"count", w.grouser_count}, {"height", w.grouser_height}, {"thickness", w.grouser_thickness}}}};
}

WheelSpec parse_wheel(const nlohmann::json& j, const std::string& where) {
  if (!j.is_object()) throw InputError(fmt::format("{}: a wheel must be a JSON object", where));
  JsonObject o(j, where, "");
  WheelSpec w;
  w.radius = o.number("radius", 0.01, 10);
  w.width = o.number("width", 0.005, 10);
  w.mass = o.number("mass", 0, 1e6, true);
  w.angular_velocity = o.number_or("angular_velocity", w.angular_velocity, 0, 100);
  if (o.has("grousers")) {
    JsonObject g = o.object("grousers");
    w.grouser_count = int(g.integer_or("count", 0, 0, 360));
    w.grouser_height = g.number_or("height", 0, 0, 0.5 * w.radius);
    w.grouser_thickness = g.number_or("thickness", 0, 0, w.radius);
    g.finish();
  }
  o.finish();
  try {
    validate(w);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", where, e.what()));
  }
  return w;
}

WheelSpec read_wheel_json(const std::string& path) { return parse_wheel(read_json_file(path, "wheel file"), path); }

void validate(const WheelRun& r) {
  terracal::check_range(WheelRanges::kDuration, r.duration, "wheel run duration");
  terracal::check_range(WheelRanges::kAverageFrom, r.average_from, "wheel run average_from");
  check_range("wheel run samples", r.samples, 2, 1e7, "");
  check_range("wheel run load_ramp", r.load_ramp, 0, r.duration, "s (at most the duration)");
  terracal::check_range(WheelRanges::kSlipAngle, r.slip_angle, "wheel run slip_angle");
  terracal::check_range(WheelRanges::kDropHeight, r.drop_height, "wheel run drop_height");
}

namespace {
void mean_sd(const std::vector<WheelSample>& s, double WheelSample::*field, double& mean, double& sd) {
  double sum = 0, sum2 = 0;
  for (const auto& x : s) sum += x.*field;
  mean = s.empty() ? 0 : sum / double(s.size());
  for (const auto& x : s) sum2 += (x.*field - mean) * (x.*field - mean);
  sd = s.size() > 1 ? std::sqrt(sum2 / double(s.size() - 1)) : 0;
}
}  // namespace

WheelResult run_wheel(const TerrainSite& site, const WheelSpec& wheel, double slip, const WheelRun& run,
                      const RigProgress& progress) {
  validate(wheel);
  validate(run);
  terracal::check_range(WheelRanges::kSlip, slip, "slip");
  const double g = norm(site.gravity());
  const double speed = wheel.angular_velocity * wheel.radius * (1 - slip);
  const double travel = speed * run.duration;
  const double cross_speed = speed * std::tan(run.slip_angle);
  const double cross_travel = cross_speed * run.duration;
  const double outer = wheel.radius + wheel.grouser_height;

  RigidBody w;
  w.name = run.slip_angle > 0 ? fmt::format("wheel at slip {}, slip angle {} rad", slip, run.slip_angle)
                              : fmt::format("wheel at slip {}", slip);
  w.shape = wheel_shape(wheel.radius, wheel.width, wheel.grouser_count, wheel.grouser_height, wheel.grouser_thickness);
  const Vec3<double> c = site.centre();
  // Start so that the run is centred on the site: the wheel ends as far past the centre as it began before it.
  w.position = {c.x - 0.5 * travel, c.y - 0.5 * cross_travel, site.surface_height() + outer + run.drop_height};
  w.mass = wheel.mass;
  w.load_ramp = run.load_ramp;
  const double iy = 0.5 * wheel.mass * wheel.radius * wheel.radius;
  const double ix = wheel.mass * (3 * wheel.radius * wheel.radius + wheel.width * wheel.width) / 12;
  w.inertia = {ix, iy, ix};
  w.motion.free = {false, false, true,
                   false, false, false};  // the axle sinks under the load; the carriage holds the rest
  w.motion.linear_velocity = {speed, cross_speed, 0};
  w.motion.angular_velocity = {0, wheel.angular_velocity,
                               0};                   // about +y: the contact point moves back, the wheel rolls +x
  check_fits(site, w, outer, wheel_reach_y(wheel));  // it starts travel/2 before the centre and ends travel/2 past it

  const auto start = std::chrono::steady_clock::now();
  auto terrain = site.make({w}, run.duration);
  const double dt = terrain->time_step();
  const long steps = long(std::ceil(run.duration / dt - 1e-9));
  const long every = std::max(1L, steps / run.samples);
  WheelResult r;
  r.slip = slip;
  r.slip_angle = run.slip_angle;
  r.load = wheel.mass * g;
  std::vector<WheelSample> steady;
  // The steadiness counts every step of the averaging window, not only the stored samples: a hop
  // can be shorter than the gap between two of them.
  const double window_start = run.average_from * run.duration - 1e-12;
  long window_steps = 0, airborne_steps = 0;
  double vertical_sum = 0, vertical_sum2 = 0;
  for (long s = 1; s <= steps; ++s) {
    terrain->step();
    if (terrain->time() >= window_start) {
      const double fz = terrain->wrenches()[0].force.z;
      ++window_steps;
      airborne_steps += fz < 0.05 * r.load;
      vertical_sum += fz;
      vertical_sum2 += fz * fz;
    }
    if (s % every != 0 && s != steps) continue;
    const BodyState& b = terrain->bodies()[0];
    const BodyWrench& f = terrain->wrenches()[0];
    const WheelSample x{
        terrain->time(), b.position.x, f.force.x, -f.torque.y, site.surface_height() - (b.position.z - outer),
        f.force.z, f.force.y};
    if (!(std::isfinite(x.dbp) && std::isfinite(x.torque) && std::isfinite(x.sinkage)))
      throw RunError(
          fmt::format("{} on {}: non-finite state at t = {:.4g} s (step {} of {} s): the step is too large for this "
                      "soil and load",
                      w.name, terrain->description(), x.t, dt, dt));
    r.series.push_back(x);
    if (x.t >= window_start) steady.push_back(x);
    if (progress) progress(w.name, x.t, run.duration);
  }
  mean_sd(steady, &WheelSample::dbp, r.dbp, r.dbp_sd);
  mean_sd(steady, &WheelSample::torque, r.torque, r.torque_sd);
  mean_sd(steady, &WheelSample::sinkage, r.sinkage, r.sinkage_sd);
  mean_sd(steady, &WheelSample::lateral, r.lateral, r.lateral_sd);
  if (window_steps > 0) {
    const double n = double(window_steps), mean = vertical_sum / n;
    r.vertical_sd = std::sqrt(std::max(0.0, vertical_sum2 / n - mean * mean));
    r.airborne_fraction = double(airborne_steps) / n;
  }
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.numerics_note = terrain->numerics_note();
  return r;
}

std::string unsteady_reason(const WheelResult& r) {
  if (r.load <= 0 || (r.airborne_fraction <= 0.01 && r.vertical_sd <= 0.25 * r.load)) return "";
  return fmt::format(
      "the wheel {} at slip {}: off the ground in {:.1f} % of the averaging window's steps, vertical force scattering "
      "by "
      "{:.2f} times the load; its means are no steady values",
      r.airborne_fraction > 0.01 ? "hops" : "is unsteady", r.slip, 100 * r.airborne_fraction, r.vertical_sd / r.load);
}

std::string steadiness_summary(const std::string& model, const std::vector<WheelResult>& results) {
  std::string unsteady;
  double worst_sd = 0, worst_airborne = 0;
  int judged = 0;
  for (const auto& r : results) {
    if (r.series.empty() || r.load <= 0) continue;  // an analytic model has no time series
    ++judged;
    worst_sd = std::max(worst_sd, r.vertical_sd / r.load);
    worst_airborne = std::max(worst_airborne, r.airborne_fraction);
    if (const std::string why = unsteady_reason(r); !why.empty()) unsteady += (unsteady.empty() ? "" : "; ") + why;
  }
  if (judged == 0) return fmt::format("{}: no time series to judge the steadiness by.", model);
  if (!unsteady.empty()) return fmt::format("**{}: unsteady.** {}.", model, unsteady);
  return fmt::format(
      "{}: every run steady (off the ground in at most {:.1f} % of the averaging window's steps; vertical force "
      "scatter at "
      "most {:.1f} % of the load).",
      model, 100 * worst_airborne, 100 * worst_sd);
}

std::vector<WheelResult> run_slip_sweep(const TerrainSite& site, const WheelSpec& wheel,
                                        const std::vector<double>& slips, const WheelRun& run,
                                        const RigProgress& progress) {
  std::vector<WheelResult> out;
  for (double s : slips) out.push_back(run_wheel(site, wheel, s, run, progress));
  return out;
}

void write_wheel_csv(const std::string& path, const std::vector<WheelResult>& results) {
  std::string s = "slip,load_N,dbp_N,torque_Nm,sinkage_m,dbp_sd_N,torque_sd_Nm\n";
  for (const auto& r : results)
    s += fmt::format("{:.6g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n", r.slip, r.load, r.dbp, r.torque, r.sinkage,
                     r.dbp_sd, r.torque_sd);
  write_text_atomically(path, s);
}

void write_wheel_series_csv(const std::string& path, const std::vector<WheelResult>& results) {
  std::string s = "slip,time_s,x_m,dbp_N,torque_Nm,sinkage_m,vertical_force_N\n";
  for (const auto& r : results)
    for (const auto& x : r.series)
      s += fmt::format("{:.6g},{:.6g},{:.6g},{:.9g},{:.9g},{:.9g},{:.9g}\n", r.slip, x.t, x.x, x.dbp, x.torque,
                       x.sinkage, x.vertical);
  write_text_atomically(path, s);
}

}  // namespace terracal::rigs
