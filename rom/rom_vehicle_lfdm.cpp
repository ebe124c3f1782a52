// LFDM vehicle files (uwsbel/low-fidelity-dynamic-models, wheeled_vehicle_models/*/data/json) read
// where their keys mean what ours do. Maps in rpm are converted to rad/s.
#include <cmath>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "rom/rom_vehicle_json.hpp"

namespace terracal::rom {

namespace {
constexpr double kRpm = 3.14159265358979323846 / 30.0;

Table1d lfdm_table(JsonObject& o, const std::string& key, double x_scale) {
  const nlohmann::json& v = o.raw(key);
  if (!v.is_array() || v.empty() || v.size() > static_cast<std::size_t>(Table1d::kMaxPoints))
    o.fail(key, fmt::format("must be a table [[x, y], ...] of 1 to {} rows", Table1d::kMaxPoints));
  Table1d t;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!v[i].is_array() || v[i].size() != 2 || !v[i][0].is_number() || !v[i][1].is_number())
      o.fail(key, fmt::format("row {} {} must be two numbers [x, y]", i + 1, v[i].dump()));
    t.x[i] = v[i][0].get<double>() * x_scale;
    t.y[i] = v[i][1].get<double>();
    if (i > 0 && !(t.x[i] > t.x[i - 1]))
      o.fail(key, fmt::format("row {} x = {}: x must increase from row to row", i + 1, v[i][0].dump()));
    t.n = static_cast<int>(i + 1);
  }
  return t;
}

// A key LFDM has and we take only at the value that means "not used".
void only(JsonObject& o, const std::string& key, const nlohmann::json& allowed, const char* why) {
  if (!o.has(key)) return;
  const nlohmann::json& v = o.raw(key);
  if (v != allowed)
    o.fail(key, fmt::format("value {} is not supported ({}); expected {}", v.dump(), why, allowed.dump()));
}
}  // namespace

RomVehicle read_lfdm_vehicle(JsonObject& o) {
  RomVehicle v;
  v.effects = kEffectTireRelaxation | kEffectRoll | kEffectRollingResistance;
  v.cg_to_front = o.number("a", 0, 100, true);
  v.cg_to_rear = o.number("b", 0, 100, true);
  v.mass = o.number("m", 0, 1e7, true);
  v.cg_height = o.number("h", 0, 100, true);
  v.yaw_inertia = o.number("jz", 0, 1e9, true);
  v.roll_inertia = o.number("jx", 0, 1e9, true);
  v.pitch_inertia = o.number_or("jy", 0.0, 0, 1e9, true);  // LFDM's 24-DOF files
  // The roll-yaw product of inertia: the 18-DOF model keeps roll and yaw uncoupled, as LFDM's does
  // for the sprung mass's quasi-static load transfer; accepted for the file to load, not used.
  if (o.has("jxz")) o.number("jxz", -1e9, 1e9);
  v.track[0] = o.number("cf", 0, 100, true);
  v.track[1] = o.number("cr", 0, 100, true);
  v.unsprung_mass[0] = o.number("muf", 0, 1e6);
  v.unsprung_mass[1] = o.number("mur", 0, 1e6);
  v.roll_center_height[0] = o.number("hrcf", -100, 100);
  v.roll_center_height[1] = o.number("hrcr", -100, 100);
  v.roll_stiffness[0] = o.number("krof", 0, 1e12, true);
  v.roll_stiffness[1] = o.number("kror", 0, 1e12, true);
  v.roll_damping[0] = o.number("brof", 0, 1e12);
  v.roll_damping[1] = o.number("bror", 0, 1e12);
  only(o, "nonLinearSteer", false, "the steering is linear in the input");
  only(o, "throttleMod", false, "the throttle is the driver's");
  only(o, "c0", 0, "use 'drag_area' and the tires' rolling resistance in our format");
  only(o, "c1", 0, "use 'drag_area' and the tires' rolling resistance in our format");
  if (o.has("step")) o.number("step", 0, 1, true);  // the step is a command-line option (--step)
  v.max_steer = o.number("maxSteer", 0, 1.5707963267948966, true, true);
  PowertrainParams& p = v.powertrain;
  p.crank_inertia = o.number("crankInertia", 0, 1e3, true);
  const nlohmann::json& ratios = o.raw("gearRatios");
  if (!ratios.is_array() || ratios.empty() || ratios.size() > PowertrainParams::kMaxGears)
    o.fail("gearRatios", fmt::format("must list 1 to {} ratios", PowertrainParams::kMaxGears));
  p.gears = static_cast<int>(ratios.size());
  for (int g = 0; g < p.gears; ++g) {
    if (!ratios[g].is_number() || !(ratios[g].get<double>() > 0))
      o.fail("gearRatios", fmt::format("value {} must be a positive number", ratios[g].dump()));
    p.gear_ratio[g] = ratios[g].get<double>();
  }
  if (o.has("shiftMap")) {
    const nlohmann::json& map = o.raw("shiftMap");
    if (!map.is_array() || static_cast<int>(map.size()) != p.gears)
      o.fail("shiftMap", fmt::format("must have one [downshift rpm, upshift rpm] row per gear ({})", p.gears));
    for (int g = 0; g < p.gears; ++g) {
      if (!map[g].is_array() || map[g].size() != 2 || !map[g][0].is_number() || !map[g][1].is_number())
        o.fail("shiftMap", fmt::format("row {} {} must be [downshift rpm, upshift rpm]", g + 1, map[g].dump()));
      p.downshift_speed[g] = map[g][0].get<double>() * kRpm;
      p.upshift_speed[g] = map[g][1].get<double>() * kRpm;
    }
  } else {
    const double up = o.number("upshiftRPM", 0, 1e5, true) * kRpm, down = o.number("downshiftRPM", 0, 1e5) * kRpm;
    for (int g = 0; g < p.gears; ++g) p.upshift_speed[g] = up, p.downshift_speed[g] = down;
  }
  p.max_torque = lfdm_table(o, "torqueMap", kRpm);
  p.losses = lfdm_table(o, "lossesMap", kRpm);
  if (o.boolean_or("tcBool", false)) v.effects |= kEffectTorqueConverter;
  p.capacity_factor = lfdm_table(o, "capacityFactorMap", 1.0);
  p.torque_ratio = lfdm_table(o, "torqueRatioMap", 1.0);
  p.max_brake_torque = o.number("maxBrakeTorque", 0, 1e7);
  const bool all = o.boolean_or("4wd", true), rear = o.boolean_or("rearWheels", true);
  p.drive = all ? Drive::kAll : rear ? Drive::kRear : Drive::kFront;
  return v;
}

}  // namespace terracal::rom
