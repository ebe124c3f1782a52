#include "highfi/vehicle/full_vehicle.hpp"

#include <fstream>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "core/vehicle/powertrain_json.hpp"
#include "core/vehicle/tmeasy_params.hpp"
#include "highfi/vehicle/vehicle_json.hpp"

namespace terracal::vehicle {
double FullVehicleSpec::total_mass() const {  // the bodies' masses (shafts have inertia only)
  double m = chassis.mass;
  if (has_steering) m += rack_steering ? rack.rack.mass : steering.link.mass + steering.arm.mass;
  for (const AxleSpec& a : axles) {
    const DoubleWishboneSpec& s = a.suspension;
    m += 2 * (s.spindle.mass + s.upright.mass + s.upper_arm.body.mass + s.lower_arm.body.mass + wheel_mass);
  }
  return m;
}

FullVehicleSpec read_full_vehicle(const nlohmann::json& j, const std::string& source) {
  if (!j.is_object()) throw InputError(fmt::format("{}: expected a JSON object (a full vehicle)", source));
  JsonObject o(j, source, "");
  FullVehicleSpec v;
  o.string_or("type", "full vehicle", {"full vehicle"});
  v.name = read_name(o, v.name);
  if (o.has("source")) o.raw("source");  // for people
  {
    JsonObject c = o.object("chassis");
    v.chassis.mass = c.number("mass", 0, 1e6, true);
    v.chassis.com = read_point(c, "com");
    v.chassis.moments = read_moments(c, "inertia");
    if (c.has("products")) v.chassis.products = read_point(c, "products");
    c.finish();
  }
  const nlohmann::json& axles = o.raw("axles");
  if (!axles.is_array() || axles.empty())
    o.fail("axles", "expected a list of axles, each {\"location\": [x, y, z], \"suspension\": {...}}");
  for (std::size_t k = 0; k < axles.size(); ++k) {
    JsonObject a(axles[k], source, fmt::format("axles[{}]", k));
    AxleSpec axle;
    axle.location = read_point(a, "location");
    axle.suspension = read_double_wishbone(a.object("suspension"));
    axle.steered = a.boolean_or("steered", false);
    a.finish();
    v.axles.push_back(axle);
  }
  if (o.has("steering")) {
    v.has_steering = true;
    JsonObject st = o.object("steering");
    v.rack_steering = st.string_or("template", "pitman_arm", {"pitman_arm", "rack_pinion"}) == "rack_pinion";
    if (v.rack_steering)
      v.rack = read_rack_pinion(st);
    else
      v.steering = read_pitman_arm(st);
  }
  for (std::size_t k = 0; k < v.axles.size(); ++k)
    if (v.axles[k].steered && !v.has_steering)
      o.fail("axles", fmt::format("axle {} is steered but the vehicle has no \"steering\"", k));
  {
    JsonObject w = o.object("wheel");
    v.wheel_mass = w.number("mass", 0, 1e4);
    v.wheel_inertia = read_moments(w, "inertia");
    v.scm_wheel.width = w.number_or("width", 0, 0.005, 10);
    if (w.has("grousers")) {
      JsonObject g = w.object("grousers");
      v.scm_wheel.grouser_count = int(g.number("count", 1, 360));
      v.scm_wheel.grouser_height = g.number("height", 0, 1);
      v.scm_wheel.grouser_thickness = g.number("thickness", 0, 1);
      g.finish();
    }
    w.finish();
  }
  if (o.has("powertrain")) {
    v.has_powertrain = true;
    v.powertrain = read_powertrain(o.object("powertrain"));
    validate_powertrain(v.powertrain, source);
  }
  if (o.has("driveline")) {
    JsonObject d = o.object("driveline");
    v.driveline.turbine_inertia = d.number_or("turbine_inertia", v.driveline.turbine_inertia, 0, 1e3, true);
    v.driveline.driveshaft_inertia = d.number_or("driveshaft_inertia", v.driveline.driveshaft_inertia, 0, 1e3, true);
    v.driveline.axle_driveshaft_inertia =
        d.number_or("axle_driveshaft_inertia", v.driveline.axle_driveshaft_inertia, 0, 1e3, true);
    d.finish();
  }
  v.tire = read_tmeasy(o.raw("tire"), source + ": tire");
  v.tire_vertical_damping = o.number_or("tire_vertical_damping", 0, 0, 1e7);
  v.scm_wheel.radius = v.tire.unloaded_radius;
  o.finish();
  return v;
}

FullVehicleSpec load_full_vehicle(const std::string& name_or_path) {
  const std::string preset = full_vehicle_preset_json(name_or_path);
  if (!preset.empty()) return read_full_vehicle(nlohmann::json::parse(preset), name_or_path + " (built in)");
  std::ifstream in(name_or_path);
  if (!in) throw InputError(fmt::format("{}: cannot open the vehicle file (or name a preset: hmmwv)", name_or_path));
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in, nullptr, true, true);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(fmt::format("{}: not valid JSON: {}", name_or_path, e.what()));
  }
  return read_full_vehicle(j, name_or_path);
}

FullVehicle::FullVehicle(const FullVehicleSpec& spec, const Vec3& origin, double ground_friction)
    : spec_(spec), system_(std::make_unique<mb::MbSystem>()) {
  mb::MbSystem& s = *system_;
  mb::RigidBody chassis;
  chassis.name = "chassis";
  chassis.mass = spec.chassis.mass;
  chassis.inertia = spec.chassis.inertia();
  chassis.position = origin + spec.chassis.com;
  chassis_ = s.add_body(chassis);
  const Mat3 wheel = spec.wheel_inertia.asDiagonal();
  const auto steering_input = [this](double t) { return driver_(t).steering; };
  if (spec.has_steering && spec.rack_steering) {
    rack_ = build_rack_pinion(s, spec.rack, chassis_, origin);
    add_rack_servo(s, spec.rack, rack_, steering_input);
  } else if (spec.has_steering) {
    steering_ = build_pitman_arm(s, spec.steering, chassis_, origin);
    add_steering_servo(s, spec.steering, steering_, steering_input);
  }
  for (const AxleSpec& a : spec.axles)
    for (double side : {1.0, -1.0}) {
      const int tierods = a.steered ? steering_link() : chassis_;
      const WishboneSide w = build_double_wishbone(s, a.suspension, chassis_, tierods, origin, a.location, side);
      // The wheel and tire turn with the spindle: their mass and inertia are the spindle's.
      mb::RigidBody& sp = s.bodies[std::size_t(w.spindle)];
      sp.mass += spec.wheel_mass;
      sp.inertia += wheel;
      corners_.push_back(w);
    }
  if (spec.has_powertrain) {
    std::vector<double> axle_inertias;
    for (const AxleSpec& a : spec.axles) axle_inertias.push_back(a.suspension.axle_inertia);
    driveline_ = build_driveline(s, spec.powertrain, spec.driveline, corners_, axle_inertias, &driver_);
  }
  s.index();
  tire_.params = spec.tire;
  tire_.vertical_damping = spec.tire_vertical_damping;
  tire_.friction = ground_friction;
  for (std::size_t wheel = 0; wheel < corners_.size(); ++wheel) {
    const int spindle = corners_[wheel].spindle;
    s.external.push_back(
        {[this, spindle, wheel](double t, const std::vector<mb::RigidBody>& b, std::vector<mb::Wrench>& f) {
           if (scm_)
             scm_->apply(wheel, t, b[std::size_t(spindle)], f[std::size_t(spindle)]);
           else
             tire_.apply(b[std::size_t(spindle)], f[std::size_t(spindle)]);
         },
         {spindle}});
  }
}

void FullVehicle::set_gear(int gear) {
  if (spec_.has_powertrain) vehicle::set_gear(*system_, spec_.powertrain, driveline_, gear);
}

bool FullVehicle::update_gear() {
  return spec_.has_powertrain && vehicle::update_gear(*system_, spec_.powertrain, driveline_);
}

std::vector<TireContact> FullVehicle::contacts() const {
  std::vector<TireContact> out;
  for (std::size_t k = 0; k < corners_.size(); ++k) {
    const mb::RigidBody& spindle = system_->bodies[std::size_t(corners_[k].spindle)];
    mb::Wrench scratch;
    out.push_back(scm_ ? scm_->contact(k, spindle) : tire_.apply(spindle, scratch));
  }
  return out;
}

void FullVehicle::use_scm(const lowfi::ScmSoil& soil, const lowfi::ScmSettings& settings) {
  if (!(spec_.scm_wheel.width > 0))
    throw InputError(
        fmt::format("{}: wheel.width is not given: the wheels cannot run on SCM soil without it", spec_.name));
  scm_ = std::make_unique<ScmWheelContact>(soil, settings, spec_.scm_wheel, corners_.size());
}

void FullVehicle::step_soil(double t) {
  if (!scm_) return;
  std::vector<int> spindles;
  for (const WishboneSide& w : corners_) spindles.push_back(w.spindle);
  scm_->step(t, system_->bodies, spindles);
}

}  // namespace terracal::vehicle
