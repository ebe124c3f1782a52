#include "rom/rom_vehicle_json.hpp"

#include <cmath>
#include <filesystem>
#include <string_view>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "core/json_file.hpp"
#include "core/json_object.hpp"
#include "core/vehicle/powertrain_json.hpp"
#include "core/vehicle/tmeasy_params.hpp"

namespace terracal::rom {

namespace {

// [front, rear] as two numbers in (lo, hi] ... or one number for both axles.
void axle_pair(JsonObject& o, const std::string& key, double* out, double lo, double hi, bool lo_open = true) {
  const nlohmann::json& v = o.raw(key);
  const nlohmann::json pair = v.is_array() ? v : nlohmann::json::array({v, v});
  if (pair.size() != 2) o.fail(key, fmt::format("value {} must be [front, rear] or one number", v.dump()));
  for (int i = 0; i < 2; ++i) {
    const bool ok = pair[i].is_number() && std::isfinite(pair[i].get<double>()) &&
                    (lo_open ? pair[i].get<double>() > lo : pair[i].get<double>() >= lo) && pair[i].get<double>() <= hi;
    if (!ok)
      o.fail(key, fmt::format("{} value {} is outside the allowed range {}{}, {}]", i == 0 ? "front" : "rear",
                              pair[i].dump(), lo_open ? "(" : "[", lo, hi));
    out[i] = pair[i].get<double>();
  }
}

void read_effects(JsonObject& o, RomVehicle& v) {
  const std::vector<std::string> names(std::begin(kRomEffectNames), std::end(kRomEffectNames));
  for (const auto& e : o.strings_or("effects", names))
    for (int i = 0; i < kRomEffectCount; ++i)
      if (e == kRomEffectNames[i]) v.effects |= 1u << i;
}

TmeasyParams tire_from(JsonObject& o, const std::string& key, const std::string& folder) {
  const nlohmann::json& t = o.raw(key);
  if (t.is_string()) {
    std::filesystem::path p = t.get<std::string>();
    if (p.is_relative()) p = std::filesystem::path(folder) / p;
    return read_tmeasy_file(p.string());
  }
  return read_tmeasy(t, fmt::format("{}: key '{}'", o.where(), key));
}

RomVehicle read_own(JsonObject& o, const std::string& folder, bool tire_given) {
  RomVehicle v;
  o.string_or("type", "ROM vehicle", {"ROM vehicle"});
  o.raw("name");
  if (o.has("source")) o.raw("source");
  for (const char* k : {"Posterior", "Fit"})  // calibrate-rom's record of how the values were found
    if (o.has(k)) o.raw(k);
  read_effects(o, v);
  v.mass = o.number("mass", 0, 1e7, true);
  axle_pair(o, "unsprung_mass", v.unsprung_mass, 0, 1e6, false);
  v.cg_to_front = o.number("cg_to_front", 0, 100, true);
  v.cg_to_rear = o.number("cg_to_rear", 0, 100, true);
  v.cg_height = o.number("cg_height", 0, 100, true);
  v.yaw_inertia = o.number("yaw_inertia", 0, 1e9, true);
  v.roll_inertia = o.number("roll_inertia", 0, 1e9, true);
  v.pitch_inertia = o.number_or("pitch_inertia", 0.0, 0, 1e9, true);
  axle_pair(o, "track", v.track, 0, 100);
  axle_pair(o, "roll_center_height", v.roll_center_height, -100, 100);
  axle_pair(o, "roll_stiffness", v.roll_stiffness, 0, 1e12);
  axle_pair(o, "roll_damping", v.roll_damping, 0, 1e12, false);
  v.max_steer = o.number("max_steer", 0, 1.5707963267948966, true, true);
  if (o.has("spring_rate")) axle_pair(o, "spring_rate", v.spring_rate, 0, 1e12);
  if (o.has("damper_rate")) axle_pair(o, "damper_rate", v.damper_rate, 0, 1e12, false);
  v.drag_area = o.number_or("drag_area", 0.0, 0, 1e3);
  v.air_density = o.number_or("air_density", 1.2, 0, 100);
  v.powertrain = read_powertrain(o.object("powertrain"));
  if (tire_given && !o.has("tire") && !o.has("tire_front")) return v;
  if (o.has("tire") && (o.has("tire_front") || o.has("tire_rear")))
    o.fail("tire", "give either 'tire' (all four) or 'tire_front' and 'tire_rear', not both");
  if (o.has("tire")) {
    v.tire[0] = v.tire[1] = tire_from(o, "tire", folder);
  } else {
    v.tire[0] = tire_from(o, "tire_front", folder);
    v.tire[1] = tire_from(o, "tire_rear", folder);
  }
  return v;
}

bool is_lfdm(const nlohmann::json& j) { return j.is_object() && j.contains("m") && j.contains("a"); }

}  // namespace

RomVehicle read_rom_vehicle(const nlohmann::json& j, const std::string& source, const std::string& folder,
                            const TmeasyParams* tire) {
  if (is_lfdm(j) && !tire)
    throw InputError(
        fmt::format("{}: an LFDM vehicle file holds no tire: give its tire file too (--tire TIRE.json)", source));
  JsonObject o(j, source, "");
  RomVehicle v = is_lfdm(j) ? read_lfdm_vehicle(o) : read_own(o, folder, tire != nullptr);
  o.finish();
  if (tire) v.tire[0] = v.tire[1] = *tire;
  validate(v, source);
  return v;
}

void validate(const RomVehicle& v, const std::string& source) {
  const PowertrainParams& p = v.powertrain;
  validate_powertrain(p, source);
  if (v.has(kEffectTorqueConverter) && (p.capacity_factor.n == 0 || p.torque_ratio.n == 0))
    throw InputError(fmt::format("{}: effect 'torque_converter' needs 'capacity_factor' and 'torque_ratio'", source));
  if (v.has(kEffectSuspension) && !(v.spring_rate[0] > 0 && v.spring_rate[1] > 0))
    throw InputError(fmt::format("{}: effect 'suspension' needs 'spring_rate' and 'damper_rate' per axle", source));
  const double hs = v.cg_height - 0.5 * (v.roll_center_height[0] + v.roll_center_height[1]);
  if (v.mass * v.gravity * hs >= v.roll_stiffness[0] + v.roll_stiffness[1])
    throw InputError(
        fmt::format("{}: roll stiffness {} N m/rad cannot hold the body up (m g hs = {:.4g} N m): the "
                    "vehicle would roll over at rest",
                    source, v.roll_stiffness[0] + v.roll_stiffness[1], v.mass * v.gravity * hs));
  validate(v.tire[0], source + " (front tire)");
  validate(v.tire[1], source + " (rear tire)");
}

RomVehicle load_rom_vehicle(const std::string& name_or_path, const std::string& tire_override) {
  TmeasyParams tire;
  if (!tire_override.empty()) tire = read_tmeasy_file(tire_override);
  const TmeasyParams* t = tire_override.empty() ? nullptr : &tire;
  const std::string preset = rom_preset_json(name_or_path);
  if (!preset.empty()) return read_rom_vehicle(nlohmann::json::parse(preset), "preset '" + name_or_path + "'", ".", t);
  const nlohmann::json j = read_json_file(name_or_path, "vehicle file");
  const std::string folder = std::filesystem::path(name_or_path).parent_path().string();
  return read_rom_vehicle(j, name_or_path, folder.empty() ? "." : folder, t);
}

}  // namespace terracal::rom
