#include "highfi/vehicle/vehicle_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <utility>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/errors.hpp"
#include "core/vtu_writer.hpp"
#include "highfi/multibody/mb_integrator.hpp"
#include "highfi/vehicle/vehicle_vtu.hpp"
#include "lowfi/scm_surface_vtu.hpp"

namespace terracal::vehicle {
namespace {
// Yaw, pitch, roll (z-y-x) of a rotation.
Vec3 yaw_pitch_roll(const Mat3& r) {
  return Vec3(std::atan2(r(1, 0), r(0, 0)), std::asin(std::clamp(-r(2, 0), -1.0, 1.0)), std::atan2(r(2, 1), r(2, 2)));
}

VehicleSample sample(const FullVehicle& v, const mb::MbIntegrator& in, double t) {
  const mb::MbSystem& s = v.system();
  const mb::RigidBody& c = s.bodies[std::size_t(v.chassis())];
  const Mat3 r = c.rotation();
  const Vec3 ypr = yaw_pitch_roll(r);
  const Vec3 vel = r.transpose() * c.velocity;
  const Vec3 acc = r.transpose() * Vec3(in.accelerations().head<3>());  // the chassis is the first body
  const Vec3 w = r * c.omega;                                           // world
  VehicleSample out;
  out.time = t;
  out.x = c.position.x(), out.y = c.position.y(), out.z = c.position.z();
  out.yaw = ypr.x(), out.pitch = ypr.y(), out.roll = ypr.z();
  out.vx = vel.x(), out.vy = vel.y();
  out.yaw_rate = w.z(), out.roll_rate = c.omega.x();
  out.ax = acc.x(), out.ay = acc.y();
  if (v.has_powertrain()) {
    out.engine_speed_rpm = s.shafts[std::size_t(v.driveline().crank)].speed * 30 / M_PI;
    out.gear = v.driveline().gear + 1;
  }
  return out;
}

// The snapshots of a run: DIR/vehicle_NNNNN.vtu at times k / rate and DIR/vehicle.pvd listing them.
// The collection is rewritten at most every 2 s of wall time while the run goes on (ParaView can open
// a run in progress), at the end, and when the run fails.
class Snapshots {
 public:
  explicit Snapshots(const VehicleRunOptions& o) : dir_(o.vtu_dir), rate_(o.vtu_rate) {
    if (dir_.empty()) return;
    if (!kVehicleVtuRate.contains(rate_))
      throw InputError(fmt::format("vehicle: the snapshot rate {} Hz is outside {}", rate_, kVehicleVtuRate.text()));
    std::filesystem::create_directories(dir_);
  }
  ~Snapshots() {
    try {
      write_collection();
    } catch (const std::exception& e) {
      spdlog::warn("vehicle: {}", e.what());
    }
  }
  Snapshots(const Snapshots&) = delete;
  Snapshots& operator=(const Snapshots&) = delete;

  // The time of the next snapshot (infinity when there are none).
  double next() const {
    return dir_.empty() ? std::numeric_limits<double>::infinity() : double(entries_.size()) / rate_;
  }
  void take(const FullVehicle& v, double t) {
    const std::string name = fmt::format("vehicle_{:05d}.vtu", entries_.size());
    write_vehicle_vtu(dir_ / name, v, t);
    if (v.scm()) {  // the soil's surface as its last step left it (at most one soil step earlier)
      const std::string soil = fmt::format("soil_{:05d}.vtu", entries_.size());
      lowfi::write_scm_surface_vtu(dir_ / soil, v.scm()->soil().terrain(), t);
      soil_entries_.emplace_back(t, soil);
    }
    entries_.emplace_back(t, name);
    if (std::chrono::steady_clock::now() - written_at_ > std::chrono::seconds(2)) write_collection();
  }
  void write_collection() {
    if (dir_.empty() || written_ == entries_.size()) return;
    write_pvd(dir_ / "vehicle.pvd", entries_);
    if (!soil_entries_.empty()) write_pvd(dir_ / "soil.pvd", soil_entries_);
    written_ = entries_.size();
    written_at_ = std::chrono::steady_clock::now();
  }
  long count() const { return long(entries_.size()); }

 private:
  std::filesystem::path dir_;
  double rate_ = 20;
  std::vector<std::pair<double, std::string>> entries_, soil_entries_;
  std::size_t written_ = 0;
  std::chrono::steady_clock::time_point written_at_{};
};
}  // namespace

void set_forward_speed(FullVehicle& v, double speed) {
  mb::MbSystem& s = v.system();
  for (mb::RigidBody& b : s.bodies)
    if (!b.fixed) b.velocity = Vec3(speed, 0, 0);
  const double spin = speed / v.spec().tire.unloaded_radius;
  for (const WishboneSide& w : v.corners()) s.bodies[std::size_t(w.spindle)].omega = Vec3(0, spin, 0);
  if (v.has_powertrain()) {
    // The gear it would have reached by this speed (as the ROMs start): in first gear at speed the
    // crank would spin far above its upshift speed, and the shift at the first step would hand the
    // crank's surplus to the chassis (5 -> 6 m/s within 0.3 s at zero throttle for the HMMWV).
    v.set_gear(starting_gear(v.spec().powertrain, spin));
    const Driveline& d = v.driveline();
    for (mb::Shaft& sh : s.shafts) sh.speed = spin;
    const double ratio = v.spec().powertrain.gear_ratio[d.gear];
    s.shafts[std::size_t(d.turbine)].speed = spin / ratio;
    s.shafts[std::size_t(d.crank)].speed = spin / ratio;
  }
}

// From rest on rigid ground onto SCM soil, as a crane lowers it: every body lifted by the deepest
// tire deflection (the wheels then just touch the surface, the suspension keeps its ride height) and
// at rest; a vertical support on each wheel carries its tire's load at first and lets go of it
// linearly over `ramp` seconds from time t, so that the soil takes the load quasi-statically (a load
// put on at once drives a wheel past its static sinkage, and the soil keeps the deeper rut).
void set_down_on_soil(FullVehicle& v, const VehicleRunOptions& o, double t, double ramp) {
  double lift = o.scm.surface_height;
  std::vector<double> loads;
  for (const TireContact& c : v.contacts()) lift = std::max(lift, o.scm.surface_height + c.deflection);
  for (const TireContact& c : v.contacts()) loads.push_back(c.fz);
  mb::MbSystem& s = v.system();
  for (mb::RigidBody& b : s.bodies)
    if (!b.fixed) b.position.z() += lift, b.velocity.setZero(), b.omega.setZero();
  for (mb::Shaft& sh : s.shafts) sh.speed = 0;
  v.use_scm(*o.soil, o.scm);
  for (std::size_t k = 0; k < loads.size(); ++k) {
    const int spindle = v.corners()[k].spindle;
    s.external.push_back({[=](double now, const std::vector<mb::RigidBody>&, std::vector<mb::Wrench>& w) {
                            w[std::size_t(spindle)].force.z() += loads[k] * std::clamp(1 - (now - t) / ramp, 0.0, 1.0);
                          },
                          {spindle}});
  }
}

VehicleRunResult run_full_vehicle(const FullVehicleSpec& spec, const DriverSeries* series, Maneuver* maneuver,
                                  const VehicleRunOptions& o) {
  if ((series == nullptr) == (maneuver == nullptr)) throw InputError("vehicle: give a driver file or a manoeuvre");
  const auto start = std::chrono::steady_clock::now();
  double lowest = 0;
  for (const AxleSpec& a : spec.axles) lowest = std::min(lowest, a.location.z() + a.suspension.spindle.com.z());
  FullVehicle v(spec, Vec3(0, 0, spec.tire.unloaded_radius - lowest), o.friction);
  // Settling: at rest on rigid ground (the springs lift the chassis to its ride height); on SCM, then
  // lifted until the wheels just touch the soil and set down on it at rest for as long again.
  const double t0 = o.soil ? 2 * o.settle_time : o.settle_time;
  // A manoeuvre's inputs: the controller's latest, reached linearly over the control period from the
  // ones before (inputs that jumped every period would cost the integrator a restart each).
  DriverInput before, latest;
  double changed_at = 0;
  v.set_driver([&](double t) {
    if (t < t0) return DriverInput{};
    if (series) return series->at(t - t0);
    const double a = std::clamp((t - changed_at) / o.control_period, 0.0, 1.0);
    return DriverInput{before.steering + a * (latest.steering - before.steering),
                       before.throttle + a * (latest.throttle - before.throttle),
                       before.braking + a * (latest.braking - before.braking)};
  });
  Snapshots snapshots(o);
  mb::MbIntegrator in(v.system(), {o.rtol, o.rtol * 1e-2, o.max_step});
  // To time t of the run's clock (settling included). On SCM, soil step by soil step from the time
  // the vehicle was set down, the integrator stopped exactly where the held wrenches change; `stop`
  // stops it exactly at t too.
  double soil_from = 0;
  long soil_steps = 0;
  const auto go = [&](double t, bool stop) {
    if (v.scm()) {
      const double h = v.scm()->time_step();
      while (soil_from + double(soil_steps + 1) * h <= t + 1e-9 * h) {
        const double ts = soil_from + double(++soil_steps) * h;
        in.advance(ts, true);
        v.step_soil(ts);
      }
      stop = true;
    }
    in.advance(t, stop);
  };
  VehicleRunResult r;
  go(o.settle_time, true);
  if (o.soil) {
    soil_from = in.time();
    set_down_on_soil(v, o, soil_from, 0.5 * o.settle_time);
    v.step_soil(soil_from);
    in.reinitialize();
    go(t0, true);
  }
  set_forward_speed(v, o.initial_speed);
  in.reinitialize();
  const double dt = 1.0 / o.output_rate;
  const double chunk = maneuver ? std::min(dt, o.control_period) : dt;
  const auto record = [&](double t) {
    r.samples.push_back(sample(v, in, t));
    const auto contacts = v.contacts();
    for (std::size_t k = 0; k < contacts.size(); ++k) r.wheels.push_back({t, int(k), contacts[k]});
  };
  record(0);
  if (snapshots.next() == 0) snapshots.take(v, 0);
  double next_row = dt;
  auto last_report = std::chrono::steady_clock::now();
  if (series)
    for (std::size_t i = 0; i < series->times().size(); ++i)
      r.inputs.push_back(
          {series->times()[i], DriverInput{series->steering()[i], series->throttle()[i], series->braking()[i]}});
  double t_prev = 0;  // the last control time
  for (long k = 1;; ++k) {
    const double t = std::min(k * chunk, o.end_time);
    if (maneuver) {
      const VehicleSample now = sample(v, in, in.time() - t0);
      before = v.driver_input(in.time());
      // Linear from here to the next control time (the ramp takes a control period, chunk at most).
      r.inputs.push_back({t_prev, before});
      t_prev = t;
      latest = maneuver->at(VehiclePose{now.time, now.x, now.y, now.yaw, now.vx});
      changed_at = in.time();
    }
    // Snapshots due before t: the integrator's state interpolated at their times (no step changes).
    for (double ts = snapshots.next(); ts < t - 1e-9; ts = snapshots.next()) {
      go(t0 + ts, false);
      snapshots.take(v, ts);
    }
    go(t0 + t, maneuver != nullptr);  // a manoeuvre's inputs change at t
    if (v.update_gear()) in.reinitialize();
    r.max_constraint_violation = std::max(r.max_constraint_violation, in.constraint_violation());
    if (t >= next_row - 1e-9 || t >= o.end_time) {
      record(t);
      next_row += dt;
    }
    if (const double ts = snapshots.next(); ts <= t + 1e-9) snapshots.take(v, ts);  // due now
    if (t >= o.end_time) {
      if (maneuver) r.inputs.push_back({t, v.driver_input(in.time())});
      break;
    }
    if (std::chrono::steady_clock::now() - last_report > std::chrono::seconds(5)) {
      last_report = std::chrono::steady_clock::now();
      const VehicleSample& now = r.samples.back();
      spdlog::info("vehicle: t = {:.3g} of {:.3g} s, speed {:.3g} m/s, gear {}, {} steps", now.time, o.end_time, now.vx,
                   now.gear, in.stats().steps);
    }
  }
  const mb::MbIntegratorStats st = in.stats();
  r.steps = st.steps;
  r.residuals = st.residuals;
  snapshots.write_collection();
  r.vtu_snapshots = snapshots.count();
  if (!o.vtu_dir.empty()) r.vtu_bodies = vehicle_body_names(v);
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace terracal::vehicle
