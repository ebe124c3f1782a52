#include "bayes/wheel_observations.hpp"

#include <cmath>
#include <set>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/csv.hpp"
#include "core/errors.hpp"

namespace terracal::bayes {
namespace {

void check_wheel_point(const WheelPoint& p, std::size_t i, const WheelGeometry& wheel, const PointLocator& where) {
  if (!(p.slip >= 0 && p.slip < 1))
    throw InputError(fmt::format("{}: slip {} is outside [0, 1); the steady wheel model drives (skids, slip < 0, "
                                 "are not modelled): leave such rows out",
                                 where(i, "slip"), p.slip));
  if (!(p.load > 0)) throw InputError(fmt::format("{}: load {} N must be > 0", where(i, "load_N"), p.load));
  if (!(p.sinkage >= 0 && p.sinkage < wheel.radius))
    throw InputError(fmt::format("{}: sinkage {} m: expected in [0, {}) (the wheel's radius); is it in millimetres?",
                                 where(i, "sinkage_m"), p.sinkage, wheel.radius));
  if (!std::isfinite(p.dbp)) throw InputError(fmt::format("{}: {} is not a number", where(i, "dbp_N"), p.dbp));
  if (!std::isfinite(p.torque))
    throw InputError(fmt::format("{}: {} is not a number", where(i, "torque_Nm"), p.torque));
}

}  // namespace

WheelData make_wheel_data(std::vector<WheelPoint> points, const WheelGeometry& wheel, const std::string& source,
                          const PointLocator& where) {
  if (!(wheel.radius > 0 && wheel.width > 0 && wheel.angular_velocity > 0))
    throw InputError(fmt::format("{}: the wheel (radius {} m, width {} m, angular velocity {} rad/s) must have a "
                                 "positive radius, width and angular velocity to be calibrated on",
                                 source, wheel.radius, wheel.width, wheel.angular_velocity));
  std::set<std::pair<double, double>> seen;
  for (std::size_t i = 0; i < points.size(); ++i) {
    check_wheel_point(points[i], i, wheel, where);
    if (!seen.insert({points[i].slip, points[i].load}).second)
      throw InputError(fmt::format("{}: a second row for slip {} at load {} N; expected one steady mean per slip and "
                                   "load",
                                   where(i, "slip"), points[i].slip, points[i].load));
  }
  if (points.size() < 2)
    throw InputError(fmt::format("{}: {} usable row(s); expected at least 2 slips to calibrate on", source,
                                 points.size()));
  return WheelData{source, wheel, std::move(points), {}};
}

WheelData load_wheel_csv(const std::string& path, const WheelGeometry& wheel) {
  const CsvTable t = CsvTable::read(path);
  t.require_columns({"slip", "load_N", "dbp_N", "torque_Nm", "sinkage_m"});
  std::vector<WheelPoint> points;
  std::vector<std::size_t> rows;  // points[k] is the table's row rows[k]
  std::vector<int> unsteady;
  for (std::size_t i = 0; i < t.rows(); ++i) {
    const auto is_nan = [&](const char* col) {
      const std::string s = t.text(i, col);
      return s == "nan" || s == "NaN" || s == "-nan";
    };
    if (is_nan("dbp_N") && is_nan("torque_Nm") && is_nan("sinkage_m")) {
      unsteady.push_back(t.line_of(i));
      continue;
    }
    WheelPoint p;
    p.line = t.line_of(i);
    p.slip = t.number(i, "slip");
    p.load = t.number(i, "load_N");
    p.dbp = t.number(i, "dbp_N");
    p.torque = t.number(i, "torque_Nm");
    p.sinkage = t.number(i, "sinkage_m");
    points.push_back(p);
    rows.push_back(i);
  }
  const PointLocator where = [&t, rows](std::size_t k, const std::string& column) {
    return t.where(rows[k], column);
  };
  WheelData d = make_wheel_data(std::move(points), wheel, path, where);
  if (!unsteady.empty())
    d.notes.push_back(fmt::format("{}: {} row(s) without steady means left out (line(s) {}): their runs were not "
                                  "steady",
                                  path, unsteady.size(), fmt::join(unsteady, ", ")));
  return d;
}

}  // namespace terracal::bayes
