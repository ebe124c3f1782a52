// Built-in manoeuvres (core/vehicle/maneuver.hpp): the open-loop steering programmes, the speed
// controller, the ISO 3888 tracks and the path follower, checked on their behaviour (a kinematic
// bicycle driven by the follower stays in the cones), and the JSON refusals.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <nlohmann/json.hpp>

#include "../../scratch_dir.hpp"
#include "../reader_cases.hpp"
#include "core/errors.hpp"
#include "core/vehicle/maneuver.hpp"

using nlohmann::json;
using terracal::DriverInput;
using terracal::InputError;
using terracal::Maneuver;
using terracal::ManeuverVehicle;
using terracal::VehiclePose;

namespace {

const ManeuverVehicle kCar{2.7, 0.6, 1.8};  // wheelbase [m], max road-wheel angle [rad], width [m]

Maneuver make(const json& j) { return Maneuver::from_json(j, "test.json", kCar); }

// The InputError message of from_json for `j`; "" when there is none.
std::string refusal(const json& j, const ManeuverVehicle& vehicle = kCar) {
  try {
    Maneuver::from_json(j, "test.json", vehicle);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// The steering that an open-loop manoeuvre gives at time t, driving at its target speed.
double steering_at(Maneuver& m, double t) { return m.at(VehiclePose{t, 0, 0, 0, m.target_speed()}).steering; }

struct Run {
  double max_error = 0;             // max |y - centreline(x)| of the reference point [m]
  double max_error_in_lanes = 0;    // the same while inside a lane
  double worst_cone_margin = -1e9;  // max over lanes of |axle point - lane centre| - (lane width - vehicle width)/2
  double end_y = 0, end_yaw = 0;
};

// A kinematic bicycle (reference point on the rear axle) at constant speed v, steered by the
// manoeuvre every dt, from x = -20 m (on the straight before lane A) to 20 m past the last lane.
Run drive_kinematic(Maneuver& m, double v, double dt = 0.005) {
  Run r;
  double x = -20, y = 0, yaw = 0, t = 0;
  const double x_end = m.gates().back().x_end + 20;
  while (x < x_end) {
    const DriverInput in = m.at(VehiclePose{t, x, y, yaw, v});
    const double delta = in.steering * kCar.max_steer_angle;
    x += v * std::cos(yaw) * dt;
    y += v * std::sin(yaw) * dt;
    yaw += v * std::tan(delta) / kCar.wheelbase * dt;
    t += dt;
    const double e = std::abs(y - m.centreline_y(x));
    r.max_error = std::max(r.max_error, e);
    const double fx = x + kCar.wheelbase * std::cos(yaw), fy = y + kCar.wheelbase * std::sin(yaw);
    for (const auto& g : m.gates()) {
      const double slack = (g.width() - kCar.width) / 2;
      if (x >= g.x_start && x <= g.x_end) {
        r.max_error_in_lanes = std::max(r.max_error_in_lanes, e);
        r.worst_cone_margin = std::max(r.worst_cone_margin, std::abs(y - g.centre()) - slack);
      }
      if (fx >= g.x_start && fx <= g.x_end)
        r.worst_cone_margin = std::max(r.worst_cone_margin, std::abs(fy - g.centre()) - slack);
    }
  }
  r.end_y = y;
  r.end_yaw = yaw;
  return r;
}

}  // namespace

TEST_CASE("maneuver: step steer is zero before the step, ramps within ramp_time and holds after it", "[maneuver]") {
  Maneuver m =
      make({{"type", "step_steer"}, {"steering", -0.4}, {"step_time", 1.0}, {"ramp_time", 0.2}, {"initial_speed", 15}});
  CHECK(m.type() == "step_steer");
  CHECK(m.target_speed() == 15);
  CHECK(m.end_time() == Approx(1.0 + 0.2 + 4));
  CHECK(steering_at(m, 0) == 0);
  CHECK(steering_at(m, 0.999) == 0);
  CHECK(steering_at(m, 1.05) == Approx(-0.1));
  CHECK(steering_at(m, 1.1) == Approx(-0.2));
  CHECK(steering_at(m, 1.2) == Approx(-0.4));
  CHECK(steering_at(m, 5) == Approx(-0.4));

  // The default ramp is 0.15 s; a ramp time of 0 is a true step.
  Maneuver d = make({{"type", "step_steer"}, {"steering", 0.5}, {"initial_speed", 10}});
  CHECK(steering_at(d, 1.075) == Approx(0.25));
  Maneuver s =
      make({{"type", "step_steer"}, {"steering", 0.5}, {"ramp_time", 0}, {"step_time", 2}, {"initial_speed", 10}});
  CHECK(steering_at(s, 1.9999) == 0);
  CHECK(steering_at(s, 2) == 0.5);
}

TEST_CASE("maneuver: single sine has the amplitude and period asked for, and is zero outside its period",
          "[maneuver]") {
  const double amplitude = 0.3, f = 0.4, t0 = 1.5, period = 1 / f;
  Maneuver m = make(
      {{"type", "single_sine"}, {"amplitude", amplitude}, {"frequency", f}, {"start_time", t0}, {"initial_speed", 20}});
  CHECK(m.end_time() == Approx(t0 + period + 3));
  double max = -1, min = 1, t_max = 0, t_min = 0, crossing = 0;
  double previous = 0;
  for (int i = 0; i <= 8000; ++i) {
    const double t = i * 1e-3;
    const double s = steering_at(m, t);
    if (t < t0 || t > t0 + period) CHECK(s == 0);
    if (s > max) max = s, t_max = t;
    if (s < min) min = s, t_min = t;
    if (t > t0 + 0.1 && previous > 0 && s <= 0 && crossing == 0) crossing = t;
    previous = s;
  }
  CHECK(max == Approx(amplitude).epsilon(1e-5));
  CHECK(min == Approx(-amplitude).epsilon(1e-5));
  CHECK(t_max == Approx(t0 + period / 4).margin(2e-3));  // left first (positive)
  CHECK(t_min == Approx(t0 + 3 * period / 4).margin(2e-3));
  CHECK(crossing == Approx(t0 + period / 2).margin(2e-3));  // the half period
}

TEST_CASE("maneuver: constant steer and straight acceleration", "[maneuver]") {
  Maneuver c = make({{"type", "constant_steer"}, {"steering", 0.2}, {"target_speed", 12}});
  CHECK(c.initial_speed() == 0);
  CHECK(c.target_speed() == 12);
  CHECK(c.end_time() == 10);
  for (double t : {0.0, 0.5, 9.0}) CHECK(steering_at(c, t) == 0.2);

  Maneuver a = make({{"type", "straight_acceleration"}, {"throttle", 0.7}, {"start_time", 2}, {"end_time", 12}});
  CHECK(a.target_speed() == 0);
  CHECK(a.end_time() == 12);
  const DriverInput before = a.at(VehiclePose{1.9, 0, 0, 0, 0});
  CHECK(before.throttle == 0);
  CHECK(before.braking == 0);
  for (double v : {0.0, 30.0}) {  // no speed controller: full throttle at any speed
    const DriverInput after = a.at(VehiclePose{2 + v, 10, 0, 0, v});
    CHECK(after.throttle == 0.7);
    CHECK(after.braking == 0);
    CHECK(after.steering == 0);
  }
}

TEST_CASE("maneuver: the speed controller opens the throttle below the target and brakes above it", "[maneuver]") {
  const json j = {{"type", "constant_steer"}, {"steering", 0}, {"target_speed", 15}};
  {
    Maneuver m = make(j);
    const DriverInput slow = m.at(VehiclePose{0, 0, 0, 0, 14});
    CHECK(slow.throttle == Approx(0.5));  // kp = 0.5 per m/s
    CHECK(slow.braking == 0);
    const DriverInput much_slower = m.at(VehiclePose{0, 0, 0, 0, 5});
    CHECK(much_slower.throttle == 1);  // clamped
  }
  {
    Maneuver m = make(j);
    const DriverInput fast = m.at(VehiclePose{0, 0, 0, 0, 16});
    CHECK(fast.throttle == 0);
    CHECK(fast.braking == Approx(0.5));
    const DriverInput at_target = m.at(VehiclePose{0.1, 0, 0, 0, 15});
    CHECK(at_target.throttle == Approx(0).margin(0.01));
    CHECK(at_target.braking == Approx(0).margin(0.01));
  }
  // Closed loop on a car with rolling resistance (0.3 m/s^2 that a steady throttle must balance):
  // the integral removes the steady error, from below (throttle) and from above (brakes).
  for (const double v0 : {8.0, 22.0}) {
    Maneuver m = make(j);
    double v = v0, t = 0, max_braking = 0;
    const double dt = 0.01;
    while (t < 40) {
      const DriverInput in = m.at(VehiclePose{t, 0, 0, 0, v});
      max_braking = std::max(max_braking, in.braking);
      v += (4.0 * in.throttle - 8.0 * in.braking - 0.3) * dt;
      t += dt;
    }
    INFO("starting at " << v0 << " m/s");
    CHECK(v == Approx(15).margin(0.02));
    CHECK((max_braking > 0.5) == (v0 > 15));
    const DriverInput steady = m.at(VehiclePose{t, 0, 0, 0, v});
    CHECK(steady.throttle == Approx(0.3 / 4.0).margin(0.01));
  }
}

TEST_CASE("maneuver: at() refuses a time that goes back, until reset()", "[maneuver]") {
  Maneuver m = make({{"type", "constant_steer"}, {"steering", 0.1}, {"initial_speed", 10}});
  m.at(VehiclePose{1, 0, 0, 0, 10});
  m.at(VehiclePose{1, 0, 0, 0, 10});  // the same time again is fine
  CHECK_THROWS_AS(m.at(VehiclePose{0.5, 0, 0, 0, 10}), terracal::RunError);
  m.reset();
  CHECK_NOTHROW(m.at(VehiclePose{0.5, 0, 0, 0, 10}));
}

TEST_CASE("maneuver: the ISO 3888 tracks have the standards' lanes and a centreline through their middles",
          "[maneuver]") {
  const double b = kCar.width;
  SECTION("ISO 3888-1") {
    Maneuver m = make({{"type", "iso3888_1"}, {"initial_speed", 20}});
    const auto& g = m.gates();
    REQUIRE(g.size() == 3);
    CHECK(g[0].x_start == 0);
    CHECK(g[0].x_end == 15);
    CHECK(g[1].x_start == 45);
    CHECK(g[1].x_end == 70);
    CHECK(g[2].x_start == 95);
    CHECK(g[2].x_end == 125);
    CHECK(g[0].width() == Approx(1.1 * b + 0.25));
    CHECK(g[1].width() == Approx(1.2 * b + 0.25));
    CHECK(g[2].width() == Approx(1.3 * b + 0.25));
    CHECK(g[0].centre() == 0);
    CHECK(g[1].y_right - g[0].y_right == Approx(3.5));  // the lane offset, to the left
    CHECK(g[2].y_right == Approx(g[0].y_right));
    CHECK(m.end_time() == Approx((125 + 30) / 20.0));
  }
  SECTION("ISO 3888-2") {
    Maneuver m = make({{"type", "iso3888_2"}, {"initial_speed", 15}});
    const auto& g = m.gates();
    REQUIRE(g.size() == 3);
    CHECK(g[0].x_end == 12);
    CHECK(g[1].x_start == 25.5);
    CHECK(g[1].x_end == 36.5);
    CHECK(g[2].x_start == 49);
    CHECK(g[2].x_end == 61);
    CHECK(g[0].width() == Approx(1.1 * b + 0.25));
    CHECK(g[1].width() == Approx(b + 1));
    CHECK(g[2].width() == Approx(3.0));  // 1.3 b + 0.25 = 2.59 m is below the 3 m minimum
    CHECK(g[1].y_right - g[0].y_left == Approx(1.0));
    CHECK(g[2].y_right == Approx(g[0].y_right));
  }
  for (const char* type : {"iso3888_1", "iso3888_2"}) {
    INFO(type);
    Maneuver left = make({{"type", type}, {"initial_speed", 20}});
    Maneuver right = make({{"type", type}, {"initial_speed", 20}, {"direction", "right"}});
    CHECK(left.centreline_y(0) == 0);
    CHECK(left.centreline_y(-50) == 0);
    for (const auto& g : left.gates())
      for (double x = g.x_start; x <= g.x_end; x += 0.5) CHECK(left.centreline_y(x) == Approx(g.centre()));
    CHECK(left.centreline_y(1000) == Approx(left.gates().back().centre()));
    for (double x = -5; x < 140; x += 0.25) {
      // Mirrored for a change to the right; the slope is the derivative of the centreline.
      CHECK(right.centreline_y(x) == Approx(-left.centreline_y(x)).margin(1e-12));
      const double h = 1e-5;
      CHECK(left.centreline_slope(x) ==
            Approx((left.centreline_y(x + h) - left.centreline_y(x - h)) / (2 * h)).margin(1e-6));
    }
  }
}

TEST_CASE("maneuver: the path follower steers toward the centreline", "[maneuver]") {
  Maneuver m = make({{"type", "iso3888_1"}, {"initial_speed", 20}});
  // On the straight of lane A, heading +x.
  CHECK(m.at(VehiclePose{0.00, 5, 1.0, 0, 20}).steering < 0);   // left of the path: steer right
  CHECK(m.at(VehiclePose{0.01, 5, -1.0, 0, 20}).steering > 0);  // right of the path: steer left
  CHECK(m.at(VehiclePose{0.02, 5, 0, 0.1, 20}).steering < 0);   // on it, heading left: steer right
  CHECK(m.at(VehiclePose{0.03, -10, 0, 0, 20}).steering == Approx(0).margin(1e-12));  // on it, aligned
  // Far off the path (farther than the lookahead) it still steers back.
  CHECK(m.at(VehiclePose{0.04, 5, 30, 0, 20}).steering < 0);
  CHECK(m.at(VehiclePose{0.045, 5, -30, 0, 20}).steering > 0);
  // Where the path turns left toward lane B, a vehicle on the path steers left.
  CHECK(m.at(VehiclePose{0.05, 20, m.centreline_y(20), 0, 20}).steering > 0);
}

TEST_CASE("maneuver: a kinematic bicycle driven by the path follower stays in the ISO 3888 cones", "[maneuver]") {
  // Measured (kinematic bicycle, wheelbase 2.7 m, width 1.8 m, 5 ms steps): ISO 3888-1 at 20 m/s
  // with the default lookahead (0.5 s): 0.42 m off the centreline at most (in the transitions), 0.15 m
  // in the lanes, axles at least 0.15 m inside the cones; with a 0.2 s lookahead 0.06 m.
  SECTION("ISO 3888-1 at 20 m/s, default lookahead") {
    Maneuver m = make({{"type", "iso3888_1"}, {"initial_speed", 20}});
    const Run r = drive_kinematic(m, 20);
    CHECK(r.max_error < 0.5);
    CHECK(r.max_error_in_lanes < 0.2);
    CHECK(r.worst_cone_margin < -0.1);  // both axles' points 0.1 m or more inside the cone lines
    CHECK(r.end_y == Approx(m.gates().back().centre()).margin(0.05));  // settled in the exit lane
    CHECK(r.end_yaw == Approx(0).margin(0.01));
  }
  SECTION("ISO 3888-1 at 20 m/s to the right, short lookahead") {
    Maneuver m = make({{"type", "iso3888_1"}, {"initial_speed", 20}, {"direction", "right"}, {"lookahead_time", 0.2}});
    CHECK(m.gates()[1].centre() < -3);
    const Run r = drive_kinematic(m, 20);
    CHECK(r.max_error < 0.1);
    CHECK(r.worst_cone_margin < -0.15);
  }
  SECTION("ISO 3888-2 at 10 m/s, default lookahead") {
    Maneuver m = make({{"type", "iso3888_2"}, {"initial_speed", 10}});
    const Run r = drive_kinematic(m, 10);
    CHECK(r.max_error < 0.45);
    CHECK(r.worst_cone_margin < -0.05);
  }
  SECTION("a longer lookahead cuts the lane changes more") {
    Maneuver short_la = make({{"type", "iso3888_1"}, {"initial_speed", 20}, {"lookahead_time", 0.3}});
    Maneuver long_la = make({{"type", "iso3888_1"}, {"initial_speed", 20}, {"lookahead_time", 0.8}});
    CHECK(drive_kinematic(short_la, 20).max_error < drive_kinematic(long_la, 20).max_error);
  }
}

TEST_CASE("maneuver: bad objects are refused, naming the key, the value and the range", "[maneuver]") {
  struct Case {
    const char* name;
    json j;
    std::vector<std::string> phrases;
  };
  const std::vector<Case> cases = {
      {"no type", {{"steering", 0.1}}, {"key 'type': is required but missing", "iso3888_1"}},
      {"unknown type", {{"type", "spiral"}}, {"key 'type': value \"spiral\" is not one of", "step_steer"}},
      {"type not a string", {{"type", 3}}, {"key 'type': value 3 is not a string"}},
      {"unknown key",
       {{"type", "single_sine"}, {"amplitude", 0.1}, {"ramp_time", 0.1}, {"initial_speed", 10}},
       {"key 'ramp_time': unknown key"}},
      {"a key of another type",
       {{"type", "straight_acceleration"}, {"target_speed", 10}},
       {"key 'target_speed': unknown key"}},
      {"steering out of range",
       {{"type", "step_steer"}, {"steering", 1.5}, {"initial_speed", 10}},
       {"key 'steering': value 1.5 is outside the allowed range [-1, 1]"}},
      {"steering missing", {{"type", "constant_steer"}, {"initial_speed", 10}}, {"key 'steering': is required"}},
      {"steering not a number",
       {{"type", "constant_steer"}, {"steering", "left"}, {"initial_speed", 10}},
       {"key 'steering': value \"left\" is not a number"}},
      {"throttle out of range",
       {{"type", "straight_acceleration"}, {"throttle", 1.2}},
       {"key 'throttle': value 1.2", "[0, 1]"}},
      {"negative speed",
       {{"type", "constant_steer"}, {"steering", 0.1}, {"initial_speed", -5}},
       {"key 'initial_speed': value -5 is outside the allowed range [0, 150] m/s"}},
      {"no speed to hold", {{"type", "constant_steer"}, {"steering", 0.1}}, {"key 'target_speed':", "above 0"}},
      {"zero frequency",
       {{"type", "single_sine"}, {"amplitude", 0.1}, {"frequency", 0}, {"initial_speed", 10}},
       {"key 'frequency': value 0 is outside the allowed range (0, 20] Hz"}},
      {"negative end time",
       {{"type", "straight_acceleration"}, {"end_time", -1}},
       {"key 'end_time': value -1", "(0, 100000] s"}},
      {"bad gain",
       {{"type", "constant_steer"}, {"steering", 0.1}, {"initial_speed", 10}, {"speed_controller", {{"kp", -1}}}},
       {"key 'speed_controller.kp': value -1 is outside the allowed range [0, 100]"}},
      {"unknown gain",
       {{"type", "constant_steer"}, {"steering", 0.1}, {"initial_speed", 10}, {"speed_controller", {{"kd", 1}}}},
       {"key 'speed_controller.kd': unknown key"}},
      {"bad direction",
       {{"type", "iso3888_2"}, {"initial_speed", 10}, {"direction", "up"}},
       {"key 'direction': value \"up\" is not one of: left, right"}},
      {"lane offset on ISO 3888-2",
       {{"type", "iso3888_2"}, {"initial_speed", 10}, {"lane_offset", 3}},
       {"key 'lane_offset': unknown key"}},
      {"zero lookahead",
       {{"type", "iso3888_1"}, {"initial_speed", 10}, {"min_lookahead", 0}},
       {"key 'min_lookahead': value 0 is outside the allowed range (0, 100] m"}},
      {"not an object", json::array({1, 2}), {"must be a JSON object"}},
  };
  for (const auto& c : cases) {
    const std::string message = refusal(c.j);
    INFO(c.name << ": the message was: " << message);
    CHECK(message.find("test.json: ") == 0);
    for (const auto& p : c.phrases) CHECK(message.find(p) != std::string::npos);
  }
  // A vehicle the manoeuvres cannot use.
  CHECK(refusal({{"type", "iso3888_1"}, {"initial_speed", 10}}, ManeuverVehicle{2.7, 0.6, 0})
            .find("key 'width': value 0 is outside the allowed range (0, 5] m") != std::string::npos);
  CHECK(refusal({{"type", "iso3888_1"}, {"initial_speed", 10}}, ManeuverVehicle{2.7, 2.0, 1.8})
            .find("key 'max_steer_angle'") != std::string::npos);
}

TEST_CASE("maneuver: read() reads a file and names it in its messages", "[maneuver]") {
  const terracal::test::ScratchDir scratch("maneuver_read");
  const std::string path = scratch.str() + "/dlc.json";
  terracal::test::write_bytes(path, R"({"type": "iso3888_1", "initial_speed": 22.2, "lane_offset": 3.0})");
  const Maneuver m = Maneuver::read(path, kCar);
  CHECK(m.type() == "iso3888_1");
  CHECK(m.initial_speed() == 22.2);
  CHECK(m.target_speed() == 22.2);
  CHECK(m.gates()[1].y_right - m.gates()[0].y_right == Approx(3.0));

  terracal::test::write_bytes(path, R"({"type": "step_steer", "steering": 0.3, "initial_speed": 10, "stepp_time": 1})");
  std::string message = terracal::test::input_error_of([](const std::string& p) { Maneuver::read(p, kCar); }, path);
  CHECK(message.find(path + ": key 'stepp_time': unknown key") == 0);
  terracal::test::write_bytes(path, "{\"type\": \"step_steer\",\n \"steering\": }");
  message = terracal::test::input_error_of([](const std::string& p) { Maneuver::read(p, kCar); }, path);
  CHECK(message.find(path + ":2:") == 0);
}
