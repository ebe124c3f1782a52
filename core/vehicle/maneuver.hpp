#pragma once
// Built-in driving manoeuvres (CPU only): a driver that turns the vehicle's pose into driver inputs
// (core/vehicle/driver_inputs.hpp), read from a JSON object.
//
//   {"type": "step_steer", "steering": 0.3, "step_time": 1.0, "initial_speed": 20, "end_time": 6}
//
// Keys every type takes:
//   "type"           one of the types below (required)
//   "initial_speed"  [m/s], in [0, 150], default 0: the speed the vehicle should start with (the
//                    caller sets it; the manoeuvre only reports it)
//   "end_time"       [s], in (0, 1e5]: how long the manoeuvre runs; the default depends on the type
// Types and their own keys (a key of another type is refused as unknown):
//   straight_acceleration  straight ahead; "throttle" (default 1, in [0, 1]) from "start_time" [s]
//                          (default 0) on, no throttle before. No speed controller. Default end 10 s.
//   constant_steer         ISO 4138 constant steering-wheel angle: "steering" (required, [-1, 1]) from
//                          the start; speed held at "target_speed". Default end 10 s.
//   step_steer             ISO 7401 step steer: steering 0 until "step_time" (default 1 s), then a
//                          linear ramp to "steering" (required) within "ramp_time" (default 0.15 s; 0
//                          is a true step); speed held. Default end step_time + ramp_time + 4 s.
//   single_sine            one period of "amplitude" sin(2 pi "frequency" (t - "start_time")) from
//                          start_time (default 1 s), frequency default 0.5 Hz, amplitude required
//                          ([-1, 1]), zero steering before and after; speed held. Default end
//                          start_time + 1/frequency + 3 s.
//   iso3888_1, iso3888_2   double lane change (ISO 3888-1) and obstacle avoidance (ISO 3888-2): a
//                          pure-pursuit path follower on the track's centreline (Maneuver::gates,
//                          centreline_y). "direction": "left" (default) or "right"; "lookahead_time"
//                          [s] (default 0.5) and "min_lookahead" [m] (default 4) give the lookahead
//                          distance max(min_lookahead, lookahead_time vx). A shorter lookahead follows
//                          the centreline more closely (a kinematic bicycle at 20 m/s on ISO 3888-1:
//                          0.06 m off at 0.2 s, 0.42 m at 0.5 s, the most where the lanes change) but
//                          damps a vehicle with tyres less (a bicycle model with linear tyres capped at
//                          0.9 g spun out of ISO 3888-1 at 20 m/s with 0.3-0.4 s). iso3888_1 also
//                          takes "lane_offset" [m] (default 3.5; how it is measured: maneuver.cpp).
//                          Speed held. Default end: the time to drive the track and 30 m more at the
//                          target speed.
// The speed-holding types take "target_speed" [m/s] (in [0, 150], default initial_speed; it must
// end up above 0) and "speed_controller": {"kp": 0.5, "ki": 0.1} (the defaults; kp in 1/(m/s), ki in
// 1/m, each in [0, 100]): a PI controller on vx whose output u goes to throttle when positive and to
// braking when negative, each clamped to [0, 1]. Steering is returned as the fraction of
// max_steer_angle, clamped to [-1, 1]. Every refusal is an InputError naming the key path, the value
// and the allowed range.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/vehicle/driver_inputs.hpp"

namespace terracal {

// What the manoeuvres need to know of the vehicle.
struct ManeuverVehicle {
  double wheelbase = 0;        // [m], in (0, 20]
  double max_steer_angle = 0;  // [rad], road-wheel angle at steering = 1, in (0, pi/2)
  double width = 0;            // [m], in (0, 5]: the ISO 3888 lane widths depend on it
};

// The vehicle's state as the driver sees it, in the ground frame of ISO 8855 (x forward, y left, z up,
// yaw counter-clockwise from +x). The path follower treats (x, y) as the point it steers about (pure
// pursuit's rear-axle centre); a centre of mass there instead shifts the steering slightly, by much
// less than the lookahead distance.
struct VehiclePose {
  double time = 0;  // [s]
  double x = 0;     // [m]
  double y = 0;     // [m]
  double yaw = 0;   // [rad]
  double vx = 0;    // [m/s], forward speed in the vehicle frame
};

// One lane (gate) of an ISO 3888 track: its cones stand along y_right and y_left from x_start to
// x_end.
struct TrackGate {
  double x_start = 0, x_end = 0;   // [m]
  double y_right = 0, y_left = 0;  // [m], y_right < y_left
  double centre() const { return 0.5 * (y_right + y_left); }
  double width() const { return y_left - y_right; }
};

class Maneuver {
 public:
  // Reads the JSON file at `path` (core/json_file.hpp) and then as from_json.
  static Maneuver read(const std::string& path, const ManeuverVehicle& vehicle);
  // `source` names the input in messages (a file's path). Throws InputError for a bad object and for
  // a vehicle outside the ranges above.
  static Maneuver from_json(const nlohmann::json& j, const std::string& source, const ManeuverVehicle& vehicle);

  // The driver inputs for the vehicle at `pose`. The speed controller integrates its error between
  // calls, so call this once per control step with non-decreasing pose.time (a call at the same
  // time adds nothing to the integral; an earlier time throws RunError). reset() starts over.
  DriverInput at(const VehiclePose& pose);
  void reset();

  std::string type() const;
  double end_time() const { return end_time_; }
  double initial_speed() const { return initial_speed_; }
  // The speed that the speed controller holds; 0 for straight_acceleration (no controller).
  double target_speed() const { return target_speed_; }

  // ISO 3888 types: the track's lanes A, B, C in driving order (empty for the other types). The path
  // starts at x = 0, y = 0 heading +x, where lane A begins.
  const std::vector<TrackGate>& gates() const { return gates_; }
  // The centreline that the path follower follows, y(x) [m]: the middle of each lane, joined by
  // quintic smoothstep transitions (continuous curvature) across the open sections between lanes;
  // 0 before lane A, the last lane's middle after it. 0 for the other types.
  double centreline_y(double x) const;
  // dy/dx of the centreline.
  double centreline_slope(double x) const;

 private:
  enum class Kind { straight_acceleration, constant_steer, step_steer, single_sine, iso3888_1, iso3888_2 };
  Maneuver() = default;
  double open_loop_steering(double t) const;
  double path_steering(const VehiclePose& pose) const;  // road-wheel angle [rad]
  void speed_control(const VehiclePose& pose, DriverInput& in);

  Kind kind_ = Kind::straight_acceleration;
  ManeuverVehicle vehicle_;
  double end_time_ = 0, initial_speed_ = 0, target_speed_ = 0;
  // straight_acceleration
  double throttle_ = 1;
  // open-loop steering: steering (constant_steer, step_steer) or amplitude (single_sine)
  double steering_ = 0, start_time_ = 0, ramp_time_ = 0, frequency_ = 0;
  // path following
  std::vector<TrackGate> gates_;
  double lookahead_time_ = 0, min_lookahead_ = 0;
  // speed controller and its state
  double kp_ = 0, ki_ = 0;
  double integral_ = 0, last_time_ = 0;
  bool started_ = false;
};

}  // namespace terracal
