#include "core/vehicle/powertrain_json.hpp"

#include <cmath>

#include <fmt/format.h>

#include "core/errors.hpp"

namespace terracal {
namespace {

constexpr double kRpm = 3.14159265358979323846 / 30.0;  // rad/s per rpm
constexpr double kBig = 1e12;

// A table [[x, y], ...]: x strictly increasing, at most Table1d::kMaxPoints rows; x scaled by
// x_scale (rpm to rad/s), y checked against [y_lo, y_hi].
Table1d table(JsonObject& o, const std::string& key, double x_scale, double y_lo, double y_hi) {
  const nlohmann::json& v = o.raw(key);
  if (!v.is_array() || v.empty() || v.size() > static_cast<std::size_t>(Table1d::kMaxPoints))
    o.fail(key, fmt::format("must be a table [[x, y], ...] of 1 to {} rows", Table1d::kMaxPoints));
  Table1d t;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const auto& row = v[i];
    if (!row.is_array() || row.size() != 2 || !row[0].is_number() || !row[1].is_number() ||
        !std::isfinite(row[0].get<double>()) || !std::isfinite(row[1].get<double>()))
      o.fail(key, fmt::format("row {} {} must be two finite numbers [x, y]", i + 1, row.dump()));
    const double x = row[0].get<double>() * x_scale, y = row[1].get<double>();
    if (i > 0 && !(x > t.x[i - 1]))
      o.fail(key, fmt::format("row {} x = {}: x must increase from row to row", i + 1, row[0].dump()));
    if (y < y_lo || y > y_hi)
      o.fail(key, fmt::format("row {} y = {} is outside the allowed range [{}, {}]", i + 1, row[1].dump(), y_lo, y_hi));
    t.x[i] = x;
    t.y[i] = y;
    t.n = static_cast<int>(i + 1);
  }
  return t;
}

// A list of up to kMaxGears positive numbers (one number: the same for every gear).
int gear_list(JsonObject& o, const std::string& key, double* out, double scale, int gears) {
  const nlohmann::json& v = o.raw(key);
  const int n = v.is_array() ? static_cast<int>(v.size()) : gears;
  if (n < 1 || n > PowertrainParams::kMaxGears || (gears > 0 && n != gears))
    o.fail(key, gears > 0 ? fmt::format("must list one value per gear ({}) or be one number", gears)
                          : fmt::format("must list 1 to {} values", PowertrainParams::kMaxGears));
  for (int i = 0; i < n; ++i) {
    const auto& x = v.is_array() ? v[i] : v;
    if (!x.is_number() || !(x.get<double>() > 0) || !std::isfinite(x.get<double>()))
      o.fail(key, fmt::format("value {} must be a positive number", x.dump()));
    out[i] = x.get<double>() * scale;
  }
  return n;
}

}  // namespace

PowertrainParams read_powertrain(JsonObject pt) {
  PowertrainParams p;
  const std::string drive = pt.string_or("drive", "all", {"all", "rear", "front"});
  p.drive = drive == "all" ? Drive::kAll : drive == "rear" ? Drive::kRear : Drive::kFront;
  p.crank_inertia = pt.number("crank_inertia", 0, 1e3, true);
  p.max_torque = table(pt, "max_torque_rpm", kRpm, -kBig, kBig);
  p.losses = pt.has("losses_rpm") ? table(pt, "losses_rpm", kRpm, -kBig, kBig) : Table1d{};
  p.capacity_factor = table(pt, "capacity_factor", 1.0, 1e-6, kBig);
  p.torque_ratio = table(pt, "torque_ratio", 1.0, 1e-6, 100);
  p.gears = gear_list(pt, "gear_ratios", p.gear_ratio, 1.0, 0);
  gear_list(pt, "upshift_rpm", p.upshift_speed, kRpm, p.gears);
  gear_list(pt, "downshift_rpm", p.downshift_speed, kRpm, p.gears);
  p.max_brake_torque = pt.number("max_brake_torque", 0, 1e7);
  pt.finish();
  return p;
}

void validate_powertrain(const PowertrainParams& p, const std::string& source) {
  for (int g = 0; g < p.gears; ++g) {
    if (g > 0 && !(p.gear_ratio[g] > p.gear_ratio[g - 1]))
      throw InputError(
          fmt::format("{}: key 'powertrain.gear_ratios': gear {} ratio {} must exceed gear {}'s {} "
                      "(wheel speed / engine speed grows with the gear)",
                      source, g + 1, p.gear_ratio[g], g, p.gear_ratio[g - 1]));
    if (!(p.downshift_speed[g] < p.upshift_speed[g]))
      throw InputError(fmt::format("{}: gear {}: downshift speed {} rpm must be below its upshift speed {} rpm", source,
                                   g + 1, p.downshift_speed[g] / kRpm, p.upshift_speed[g] / kRpm));
  }
  for (int i = 1; i < p.torque_ratio.n; ++i)
    if (p.torque_ratio.y[i] > p.torque_ratio.y[i - 1])
      throw InputError(
          fmt::format("{}: key 'powertrain.torque_ratio': row {} ratio {} rises; the converter's torque "
                      "ratio must not grow with the speed ratio",
                      source, i + 1, p.torque_ratio.y[i]));
}

}  // namespace terracal
