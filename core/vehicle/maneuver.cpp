#include "core/vehicle/maneuver.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/errors.hpp"
#include "core/json_file.hpp"
#include "core/json_object.hpp"
#include "core/range.hpp"

namespace terracal {
namespace {

const std::vector<std::string> kTypes = {"straight_acceleration", "constant_steer", "step_steer",
                                         "single_sine",           "iso3888_1",      "iso3888_2"};

constexpr Range kSpeed{0, 150, false, false, "m/s"};
constexpr Range kEndTime{0, 1e5, true, false, "s"};
constexpr Range kTimeOfDay{0, 1e4, false, false, "s"};  // start_time, step_time
constexpr Range kRampTime{0, 10, false, false, "s"};
constexpr Range kFrequency{0, 20, true, false, "Hz"};
constexpr Range kSteering{-1, 1};
constexpr Range kFraction{0, 1};
constexpr Range kGain{0, 100};
constexpr Range kLookaheadTime{0, 5, false, false, "s"};
constexpr Range kMinLookahead{0, 100, true, false, "m"};
constexpr Range kLaneOffset{0, 20, false, false, "m"};

constexpr Range kWheelbase{0, 20, true, false, "m"};
constexpr Range kMaxSteer{0, std::numbers::pi / 2, true, true, "rad"};
constexpr Range kWidth{0, 5, true, false, "m"};

// Quintic smoothstep on [0, 1] and its derivative: zero slope and curvature at both ends, so the
// centreline's curvature is continuous where a transition meets a lane.
double smoothstep5(double s) { return s * s * s * (10 + s * (-15 + 6 * s)); }
double smoothstep5_slope(double s) { return 30 * s * s * (1 - s) * (1 - s); }

// The lanes of the ISO 3888 tracks for a vehicle of width b [m], for a lane change to the left (the
// caller mirrors them for one to the right). Lane A is centred on y = 0 and starts at x = 0.
//
// Sources (the standards themselves are not public; these agree on the lengths and widths):
//   - Project Chrono, demo_VEH_HMMWV_DoubleLaneChange.cpp (R. Serban, R. Gericke), class
//     ISO3888_Wrapper: both tracks, their lengths, widths and offsets;
//   - AhmadAmine998/iso_maneuvers, generate_DLC_info.py: ISO 3888-2 (12 / 13.5 / 11 / 12.5 / 12 m,
//     widths 1.1 b + 0.25, b + 1, a 1 m offset of lane B);
//   - mathworks/Simscape-Vehicle-Templates, sm_car_trajectory_double_lane_change_iso3888.m, and a
//     Modelica "Tricycle" package quoting ISO 3888-1:1999 Table 1: 15 / 30 / 25 / 25 / 15 + 15 m,
//     a 3.5 m lane offset.
// ISO 3888-1 (double lane change), total 125 m:
//   section 1 (lane A) 15 m long, 1.1 b + 0.25 wide; section 2, 30 m open; section 3 (lane B) 25 m
//   long, 1.2 b + 0.25 wide, offset 3.5 m to the left; section 4, 25 m open; sections 5 and 6
//   (lane C) 15 + 15 m long, 1.3 b + 0.25 wide.
//   Where the 3.5 m is measured from differs between the sources (Chrono: from lane A's centreline
//   to lane B's right-hand cones; MathWorks: between the lane centres). Here it is the distance
//   between the right-hand cone lines of lanes A and B (our reading of the standard's figure, not
//   checked against the standard itself; the `lane_offset` key changes it). Lane C's right-hand
//   cones are in line with lane A's (as in Chrono).
// ISO 3888-2 (obstacle avoidance), total 61 m:
//   section 1 (lane A) 12 m long, 1.1 b + 0.25 wide; section 2, 13.5 m open; section 3 (lane B) 11 m
//   long, b + 1 wide, its right-hand cones 1 m to the left of lane A's left-hand cones; section 4,
//   12.5 m open; section 5 (lane C) 12 m long, 1.3 b + 0.25 wide but at least 3 m (our reading;
//   Chrono uses 3 m flat, iso_maneuvers min(1.3 b + 0.25, 3 m)), its right-hand cones in line with
//   lane A's.
std::vector<TrackGate> iso3888_gates(bool part2, double b, double lane_offset) {
  const auto gate = [](double x0, double length, double y_right, double width) {
    return TrackGate{x0, x0 + length, y_right, y_right + width};
  };
  std::vector<TrackGate> g;
  if (!part2) {
    const double wa = 1.1 * b + 0.25, wb = 1.2 * b + 0.25, wc = 1.3 * b + 0.25;
    g.push_back(gate(0, 15, -wa / 2, wa));
    g.push_back(gate(45, 25, -wa / 2 + lane_offset, wb));
    g.push_back(gate(95, 30, -wa / 2, wc));
  } else {
    const double wa = 1.1 * b + 0.25, wb = b + 1, wc = std::max(1.3 * b + 0.25, 3.0);
    g.push_back(gate(0, 12, -wa / 2, wa));
    g.push_back(gate(25.5, 11, wa / 2 + 1, wb));
    g.push_back(gate(49, 12, -wa / 2, wc));
  }
  return g;
}

}  // namespace

Maneuver Maneuver::read(const std::string& path, const ManeuverVehicle& vehicle) {
  return from_json(read_json_file(path, "maneuver file"), path, vehicle);
}

Maneuver Maneuver::from_json(const nlohmann::json& j, const std::string& source, const ManeuverVehicle& vehicle) {
  check_range(kWheelbase, vehicle.wheelbase, "wheelbase", source + " (vehicle)");
  check_range(kMaxSteer, vehicle.max_steer_angle, "max_steer_angle", source + " (vehicle)");
  check_range(kWidth, vehicle.width, "width", source + " (vehicle)");

  JsonObject o(j, source, "");
  if (!o.has("type"))
    o.fail("type", fmt::format("is required but missing; expected one of: {}", fmt::join(kTypes, ", ")));
  const std::string type = o.string_or("type", "", kTypes);
  Maneuver m;
  m.vehicle_ = vehicle;
  m.kind_ = static_cast<Kind>(std::find(kTypes.begin(), kTypes.end(), type) - kTypes.begin());
  m.initial_speed_ = o.number_or("initial_speed", 0, kSpeed);

  double default_end = 10;
  if (m.kind_ == Kind::straight_acceleration) {
    m.throttle_ = o.number_or("throttle", 1, kFraction);
    m.start_time_ = o.number_or("start_time", 0, kTimeOfDay);
  } else {
    m.target_speed_ = o.number_or("target_speed", m.initial_speed_, kSpeed);
    if (!(m.target_speed_ > 0))
      o.fail("target_speed", fmt::format("the target speed is {} m/s; expected a speed above 0 (give target_speed, "
                                         "or an initial_speed above 0 that it defaults to)",
                                         m.target_speed_));
    m.kp_ = 0.5;
    m.ki_ = 0.1;
    if (o.has("speed_controller")) {
      JsonObject pi = o.object("speed_controller");
      m.kp_ = pi.number_or("kp", m.kp_, kGain);
      m.ki_ = pi.number_or("ki", m.ki_, kGain);
      pi.finish();
    }
    switch (m.kind_) {
      case Kind::constant_steer:
        m.steering_ = o.number("steering", kSteering);
        break;
      case Kind::step_steer:
        m.steering_ = o.number("steering", kSteering);
        m.start_time_ = o.number_or("step_time", 1, kTimeOfDay);
        m.ramp_time_ = o.number_or("ramp_time", 0.15, kRampTime);
        default_end = m.start_time_ + m.ramp_time_ + 4;
        break;
      case Kind::single_sine:
        m.steering_ = o.number("amplitude", kSteering);
        m.frequency_ = o.number_or("frequency", 0.5, kFrequency);
        m.start_time_ = o.number_or("start_time", 1, kTimeOfDay);
        default_end = m.start_time_ + 1 / m.frequency_ + 3;
        break;
      case Kind::iso3888_1:
      case Kind::iso3888_2: {
        const bool part2 = m.kind_ == Kind::iso3888_2;
        const bool left = o.string_or("direction", "left", {"left", "right"}) == "left";
        const double offset = part2 ? 0 : o.number_or("lane_offset", 3.5, kLaneOffset);
        m.lookahead_time_ = o.number_or("lookahead_time", 0.5, kLookaheadTime);
        m.min_lookahead_ = o.number_or("min_lookahead", 4, kMinLookahead);
        m.gates_ = iso3888_gates(part2, vehicle.width, offset);
        if (!left)
          for (TrackGate& g : m.gates_) g = TrackGate{g.x_start, g.x_end, -g.y_left, -g.y_right};
        default_end = (m.gates_.back().x_end + 30) / m.target_speed_;
        break;
      }
      case Kind::straight_acceleration:
        break;
    }
  }
  m.end_time_ = o.number_or("end_time", std::min(default_end, kEndTime.hi), kEndTime);
  o.finish();
  return m;
}

std::string Maneuver::type() const { return kTypes[static_cast<std::size_t>(kind_)]; }

void Maneuver::reset() {
  integral_ = 0;
  last_time_ = 0;
  started_ = false;
}

double Maneuver::centreline_y(double x) const {
  if (gates_.empty()) return 0;
  if (x <= gates_[0].x_end) return gates_[0].centre();
  for (std::size_t i = 1; i < gates_.size(); ++i) {
    const TrackGate& a = gates_[i - 1];
    const TrackGate& b = gates_[i];
    if (x < b.x_start)
      return a.centre() + (b.centre() - a.centre()) * smoothstep5((x - a.x_end) / (b.x_start - a.x_end));
    if (x <= b.x_end) return b.centre();
  }
  return gates_.back().centre();
}

double Maneuver::centreline_slope(double x) const {
  for (std::size_t i = 1; i < gates_.size(); ++i) {
    const TrackGate& a = gates_[i - 1];
    const TrackGate& b = gates_[i];
    if (x > a.x_end && x < b.x_start)
      return (b.centre() - a.centre()) * smoothstep5_slope((x - a.x_end) / (b.x_start - a.x_end)) /
             (b.x_start - a.x_end);
  }
  return 0;
}

double Maneuver::open_loop_steering(double t) const {
  switch (kind_) {
    case Kind::constant_steer:
      return steering_;
    case Kind::step_steer:
      if (t < start_time_) return 0;
      if (t >= start_time_ + ramp_time_) return steering_;
      return steering_ * (t - start_time_) / ramp_time_;
    case Kind::single_sine:
      if (t < start_time_ || t > start_time_ + 1 / frequency_) return 0;
      return steering_ * std::sin(2 * std::numbers::pi * frequency_ * (t - start_time_));
    default:
      return 0;
  }
}

// Pure pursuit (Coulter, "Implementation of the pure pursuit path tracking algorithm", CMU-RI-TR-92-01):
// the target is the centreline's point ahead of the vehicle at the lookahead distance ld; the wheel
// angle puts the vehicle on the circle through it, delta = atan(2 L sin(alpha) / ld), alpha the
// target's bearing from the vehicle's heading.
double Maneuver::path_steering(const VehiclePose& p) const {
  const double ld = std::max(min_lookahead_, lookahead_time_ * std::abs(p.vx));
  const auto distance2 = [&](double xt) {
    const double dx = xt - p.x, dy = centreline_y(xt) - p.y;
    return dx * dx + dy * dy;
  };
  double xt = p.x + ld;  // farther than ld from the path: head for the point ld ahead
  if (distance2(p.x) < ld * ld) {
    // distance2 grows from below ld^2 at p.x to at least ld^2 at p.x + ld: bisect for ld.
    double lo = p.x, hi = p.x + ld;
    for (int i = 0; i < 60 && hi - lo > 1e-9; ++i) {
      const double mid = 0.5 * (lo + hi);
      (distance2(mid) < ld * ld ? lo : hi) = mid;
    }
    xt = hi;
  }
  const double dx = xt - p.x, dy = centreline_y(xt) - p.y;
  const double d = std::hypot(dx, dy);
  const double alpha = std::atan2(dy, dx) - p.yaw;
  return std::atan2(2 * vehicle_.wheelbase * std::sin(alpha), d);
}

void Maneuver::speed_control(const VehiclePose& p, DriverInput& in) {
  const double dt = started_ ? p.time - last_time_ : 0;
  const double e = target_speed_ - p.vx;
  // Conditional integration (anti-windup): the integral stops growing while the output is saturated
  // in the direction the error pushes it.
  const double trial = kp_ * e + ki_ * (integral_ + e * dt);
  if (std::abs(trial) < 1 || (trial > 0) != (e > 0)) integral_ += e * dt;
  const double u = kp_ * e + ki_ * integral_;
  in.throttle = std::clamp(u, 0.0, 1.0);
  in.braking = std::clamp(-u, 0.0, 1.0);
}

DriverInput Maneuver::at(const VehiclePose& pose) {
  if (!std::isfinite(pose.time) || (started_ && pose.time < last_time_))
    throw RunError(
        fmt::format("maneuver {}: the pose's time {} s is before the previous call's {} s; expected one "
                    "call per control step in time order (or reset() to start over)",
                    type(), pose.time, last_time_));
  DriverInput in;
  switch (kind_) {
    case Kind::straight_acceleration:
      in.throttle = pose.time >= start_time_ ? throttle_ : 0;
      break;
    case Kind::iso3888_1:
    case Kind::iso3888_2:
      in.steering = std::clamp(path_steering(pose) / vehicle_.max_steer_angle, -1.0, 1.0);
      speed_control(pose, in);
      break;
    default:
      in.steering = std::clamp(open_loop_steering(pose.time), -1.0, 1.0);
      speed_control(pose, in);
      break;
  }
  last_time_ = pose.time;
  started_ = true;
  return in;
}

}  // namespace terracal
