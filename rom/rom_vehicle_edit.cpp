#include "rom/rom_vehicle_edit.hpp"

#include <filesystem>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "core/json_file.hpp"
#include "rom/batch_vary.hpp"
#include "rom/rom_vehicle_json.hpp"

namespace terracal::rom {
namespace {

using json = nlohmann::ordered_json;

// Key `key` of an axle pair (a number for both axles, or [front, rear]) with one axle's value set.
void set_axle(json& j, const std::string& key, int axle, double value) {
  json pair = j.contains(key) && j[key].is_array() ? j[key] : json::array({j.value(key, 0.0), j.value(key, 0.0)});
  pair[axle] = value;
  j[key] = pair;
}

// As apply_vary_parameter: the sum keeps the file's front share, the share keeps its sum.
void set_roll_stiffness_sum_or_share(json& j, bool sum, double x) {
  const json& k = j["roll_stiffness"];
  const double front = k.is_array() ? k[0].get<double>() : k.get<double>();
  const double rear = k.is_array() ? k[1].get<double>() : k.get<double>();
  const double share = sum ? front / (front + rear) : x;
  const double total = sum ? x : front + rear;
  j["roll_stiffness"] = json::array({share * total, (1 - share) * total});
}

// The tires as tire_front and tire_rear objects (a tire file's content read in).
void split_tires(json& j, const std::string& folder) {
  const auto load = [&](const json& t) -> json {
    if (!t.is_string()) return t;
    std::filesystem::path p = t.get<std::string>();
    if (p.is_relative()) p = std::filesystem::path(folder) / p;
    return json::parse(read_json_file(p.string(), "tire file").dump());
  };
  if (j.contains("tire")) {
    const json t = load(j["tire"]);
    j.erase("tire");
    j["tire_front"] = t;
    j["tire_rear"] = t;
  } else {
    j["tire_front"] = load(j["tire_front"]);
    j["tire_rear"] = load(j["tire_rear"]);
  }
}

void scale_df0(json& tire, const char* direction, double factor, const json& base_tire) {
  if (!tire.contains(direction) || !tire[direction].contains("df0"))
    throw InputError(
        fmt::format("the vehicle's tire has no '{}.df0' (a tire given by its parameter guess): write "
                    "the tire's curves out to calibrate a stiffness scale",
                    direction));
  json& df0 = tire[direction]["df0"];
  for (std::size_t l = 0; l < df0.size(); ++l) df0[l] = factor * base_tire[direction]["df0"][l].get<double>();
}

}  // namespace

bool is_run_setting(const std::string& name) { return name == "friction" || name == "gravity"; }

nlohmann::ordered_json vehicle_json_with(const std::string& name_or_path, const std::vector<std::string>& names,
                                         const std::vector<double>& values) {
  const std::string preset = rom_preset_json(name_or_path);
  json j = preset.empty() ? json::parse(read_json_file(name_or_path, "vehicle file").dump()) : json::parse(preset);
  if (j.contains("m") && j.contains("a"))
    throw InputError(
        fmt::format("{}: an LFDM vehicle file; calibrate-rom writes terracal's vehicle format, so give "
                    "the vehicle in that format (docs/formats.md, \"ROM vehicle\")",
                    name_or_path));
  const std::string folder =
      preset.empty() ? std::filesystem::path(name_or_path).parent_path().string() : std::string(".");
  split_tires(j, folder.empty() ? "." : folder);
  const json base = j;
  for (std::size_t k = 0; k < names.size(); ++k) {
    const std::string& n = names[k];
    const double x = values[k];
    if (is_run_setting(n))
      throw InputError(fmt::format("parameter '{}': a run setting, not part of a vehicle file", n));
    if (n == "mass" || n == "cg_height" || n == "yaw_inertia" || n == "roll_inertia" || n == "max_steer" ||
        n == "drag_area") {
      j[n] = x;
    } else if (n == "cg_to_front") {
      j["cg_to_rear"] = base["cg_to_front"].get<double>() + base["cg_to_rear"].get<double>() - x;
      j["cg_to_front"] = x;
    } else if (n == "roll_stiffness_total" || n == "roll_stiffness_front_share") {
      set_roll_stiffness_sum_or_share(j, n == "roll_stiffness_total", x);
    } else if (n.rfind("roll_stiffness_", 0) == 0 || n.rfind("roll_damping_", 0) == 0) {
      const bool front = n.ends_with("_front");
      set_axle(j, n.substr(0, n.rfind('_')), front ? 0 : 1, x);
    } else if (n == "max_brake_torque") {
      j["powertrain"]["max_brake_torque"] = x;
    } else if (n == "torque_scale") {
      json& map = j["powertrain"]["max_torque_rpm"];
      for (std::size_t i = 0; i < map.size(); ++i)
        map[i][1] = x * base["powertrain"]["max_torque_rpm"][i][1].get<double>();
    } else if (n == "tire_cornering_scale" || n == "tire_longitudinal_scale") {
      const char* dir = n == "tire_cornering_scale" ? "lateral" : "longitudinal";
      for (const char* t : {"tire_front", "tire_rear"}) scale_df0(j[t], dir, x, base[t]);
    } else if (n == "tire_cornering_scale_front" || n == "tire_cornering_scale_rear") {
      const char* t = n.ends_with("_front") ? "tire_front" : "tire_rear";
      scale_df0(j[t], "lateral", x, base[t]);
    } else if (n == "rolling_resistance") {
      for (const char* t : {"tire_front", "tire_rear"}) j[t]["rolling_resistance"] = x;
    } else {
      throw InputError(fmt::format("parameter '{}': not a vehicle parameter; expected one of {}", n,
                                   fmt::format("{}", fmt::join(vary_parameter_names(), ", "))));
    }
  }
  return j;
}

}  // namespace terracal::rom
