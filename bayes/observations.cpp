#include "bayes/observations.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include <fmt/format.h>

#include "core/csv.hpp"
#include "core/errors.hpp"

namespace terracal::bayes {
namespace {

// A bevameter plate sinks centimetres to decimetres and has a radius of centimetres to decimetres.
// Values this large are almost surely millimetres: refuse them rather than fit nonsense.
constexpr double kMaxPlausibleSinkage = 1.0;  // m
constexpr double kMaxPlausibleRadius = 2.0;   // m

// A curve starts at about zero and, simulated or measured, can dip a hair below it: that is noise,
// not a sign error. A value below -kZeroNoise x the largest magnitude of its column is refused.
constexpr double kZeroNoise = 0.02;

void require_positive(const std::string& where, double v) {
  if (!(v > 0)) throw InputError(fmt::format("{}: {} must be > 0", where, v));
}

void reject_millimetres(const std::string& where, const std::string& col, double v, double limit, const char* what) {
  if (v > limit)
    throw InputError(
        fmt::format("{}: {} = {} m is implausible for a bevameter {} (expected at most {} m); "
                    "the file looks like it is in millimetres: convert to metres",
                    where, col, v, what, limit));
}

template <class Point>
double largest_magnitude(const std::vector<Point>& points, double Point::*field) {
  double m = 0;
  for (const auto& p : points) m = std::max(m, std::abs(p.*field));
  return m;
}

// The checks on one plate point alone.
void check_plate_point(const PlatePoint& p, std::size_t i, const PointLocator& where, double force_noise) {
  require_positive(where(i, "plate_radius_m"), p.radius);
  if (p.sinkage < 0)
    throw InputError(fmt::format("{}: sinkage {} m is negative; expected >= 0", where(i, "sinkage_m"), p.sinkage));
  if (p.force < -force_noise)
    throw InputError(
        fmt::format("{}: force {} N is negative; a plate pushed into soil meets a force >= 0 (values down to "
                    "-{} % of the largest force, {} N, pass as noise; remove the sensor offset, or check the "
                    "sign convention)",
                    where(i, "force_N"), p.force, 100 * kZeroNoise, force_noise));
  reject_millimetres(where(i, "plate_radius_m"), "plate_radius_m", p.radius, kMaxPlausibleRadius, "plate radius");
  reject_millimetres(where(i, "sinkage_m"), "sinkage_m", p.sinkage, kMaxPlausibleSinkage, "plate sinkage");
}

// Per plate, what its rows so far have reached: which rows lie on the virgin curve that the Bekker
// law describes (PlatePoint::fitted), and what the next row may be, depend on it.
struct PlateHistory {
  double deepest = 0;           // the deepest sinkage so far
  double strongest = 0;         // the largest force so far
  bool back_on_virgin = false;  // this reload is back on the virgin curve
  const PlatePoint* previous = nullptr;
  const PlatePoint* deepest_row = nullptr;
};

// The rows of a plate are its test's history (an unload or reload branch is a run of consecutive
// rows), so they must come in the order of the test: loading deepens the plate beyond every earlier
// row, unloading raises it, a reload follows an unload and deepens it again. Throws naming the first
// row that breaks this, and the row it contradicts.
void check_test_order(const PlatePoint& p, std::size_t i, const PointLocator& where, const PlateHistory& h) {
  const std::string in_order =
      "the rows of a plate must be in the order of the test (sort them by time); where the plate was unloaded, "
      "label the rows with the phase column (load, unload, reload)";
  const PlatePoint* prev = h.previous;
  if (p.phase == PlatePhase::kLoad && h.deepest_row && p.sinkage < h.deepest)
    throw InputError(
        fmt::format("{}: load row at sinkage {} m is shallower than line {} of the plate r = {} m ({} m); "
                    "loading deepens the plate: expected at least {} m; {}",
                    where(i, "sinkage_m"), p.sinkage, h.deepest_row->line, p.radius, h.deepest, h.deepest, in_order));
  if (p.phase == PlatePhase::kUnload && p.sinkage > h.deepest)
    throw InputError(
        fmt::format("{}: unload row at sinkage {} m is deeper than the deepest sinkage so far of the plate "
                    "r = {} m ({} m); expected at most {} m (is the phase column right? {})",
                    where(i, "sinkage_m"), p.sinkage, p.radius, h.deepest, h.deepest, in_order));
  if (p.phase == PlatePhase::kUnload && prev && prev->phase == PlatePhase::kUnload && p.sinkage > prev->sinkage)
    throw InputError(
        fmt::format("{}: unload row at sinkage {} m is deeper than the unload row before it (line {}, "
                    "{} m); unloading raises the plate: expected at most {} m; {}",
                    where(i, "sinkage_m"), p.sinkage, prev->line, prev->sinkage, prev->sinkage, in_order));
  if (p.phase == PlatePhase::kReload && (!prev || prev->phase == PlatePhase::kLoad))
    throw InputError(fmt::format(
        "{}: reload row{} of the plate r = {} m without an unload row before it; expected a "
        "reload to follow an unload; {}",
        where(i, "phase"), prev ? fmt::format(" after the load row of line {}", prev->line) : "", p.radius, in_order));
  if (p.phase == PlatePhase::kReload && prev->phase == PlatePhase::kReload && p.sinkage < prev->sinkage)
    throw InputError(
        fmt::format("{}: reload row at sinkage {} m is shallower than the reload row before it (line {}, "
                    "{} m); reloading deepens the plate: expected at least {} m; {}",
                    where(i, "sinkage_m"), p.sinkage, prev->line, prev->sinkage, prev->sinkage, in_order));
}

void mark_fitted(PlatePoint& p, std::size_t i, const PointLocator& where, PlateHistory& h) {
  check_test_order(p, i, where, h);
  // Every loading row below the surface is on the virgin curve (the order check keeps it at or
  // beyond the deepest sinkage so far). A reload first climbs its elastic branch (in SCM up the
  // unload line to the old deepest point); it is back on the virgin curve once it is deeper than
  // before and its force passes the largest force so far. Once there it stays there until the next
  // unload: a noisy force (a CRM curve) that dips below the old largest force is still virgin
  // loading, not a new elastic branch of one row.
  if (p.phase == PlatePhase::kUnload) h.back_on_virgin = false;
  if (p.phase == PlatePhase::kLoad)
    p.fitted = p.sinkage > 0;
  else
    p.fitted = p.phase == PlatePhase::kReload && p.sinkage > 0 && p.sinkage > h.deepest &&
               (h.back_on_virgin || p.force >= h.strongest);
  if (p.phase == PlatePhase::kReload && p.fitted) h.back_on_virgin = true;
  if (!h.deepest_row || p.sinkage > h.deepest) h.deepest_row = &p;
  h.deepest = std::max(h.deepest, p.sinkage);
  if (p.phase != PlatePhase::kReload || p.fitted) h.strongest = std::max(h.strongest, p.force);
  h.previous = &p;
}

// The indices of the points grouped by plate radius, plates in the order they first appear, each
// plate's rows in their own order: plates may be interleaved in a file, a plate's rows may not.
std::vector<std::size_t> grouped_by_plate(const std::vector<PlatePoint>& points) {
  std::vector<double> plates;
  for (const auto& p : points)
    if (std::find(plates.begin(), plates.end(), p.radius) == plates.end()) plates.push_back(p.radius);
  std::vector<std::size_t> order;
  for (double r : plates)
    for (std::size_t i = 0; i < points.size(); ++i)
      if (points[i].radius == r) order.push_back(i);
  return order;
}

void check_shear_point(const ShearPoint& p, std::size_t i, const PointLocator& where, double torque_noise) {
  if (p.inner_radius < 0)
    throw InputError(fmt::format("{}: {} m is negative; expected >= 0", where(i, "inner_radius_m"), p.inner_radius));
  require_positive(where(i, "outer_radius_m"), p.outer_radius);
  if (p.outer_radius <= p.inner_radius)
    throw InputError(fmt::format("{}: outer radius {} m must exceed the inner radius {} m", where(i, "outer_radius_m"),
                                 p.outer_radius, p.inner_radius));
  reject_millimetres(where(i, "outer_radius_m"), "outer_radius_m", p.outer_radius, kMaxPlausibleRadius,
                     "annulus radius");
  require_positive(where(i, "normal_load_N"), p.normal_load);
  if (p.torque < -torque_noise)
    throw InputError(
        fmt::format("{}: torque {} N m is negative; expected >= 0 (values down to -{} % of the largest torque, "
                    "{} N m, pass as noise; check the sign convention)",
                    where(i, "torque_Nm"), p.torque, 100 * kZeroNoise, torque_noise));
  if (p.angle < 0)
    throw InputError(
        fmt::format("{}: shear angle {} rad is negative; expected >= 0 (or empty for the developed torque)",
                    where(i, "angle_rad"), p.angle));
}

PointLocator csv_locator(const CsvTable& t) {
  return [&t](std::size_t row, const std::string& column) { return t.where(row, column); };
}

}  // namespace

int PlateData::fitted_count() const {
  return static_cast<int>(std::count_if(points.begin(), points.end(), [](const PlatePoint& p) { return p.fitted; }));
}

std::optional<PlatePhase> parse_plate_phase(const std::string& text) {
  if (text.empty() || text == "load") return PlatePhase::kLoad;
  if (text == "unload") return PlatePhase::kUnload;
  if (text == "reload") return PlatePhase::kReload;
  return std::nullopt;
}

PlateData make_plate_data(std::vector<PlatePoint> points, const std::string& source, const PointLocator& where) {
  PlateData d;
  d.path = source;
  const double force_noise = kZeroNoise * largest_magnitude(points, &PlatePoint::force);
  for (std::size_t i = 0; i < points.size(); ++i) check_plate_point(points[i], i, where, force_noise);
  std::map<double, PlateHistory> history;  // per plate radius; in file order, so the first bad row is named
  for (std::size_t i = 0; i < points.size(); ++i) mark_fitted(points[i], i, where, history[points[i].radius]);
  for (std::size_t i : grouped_by_plate(points)) d.points.push_back(points[i]);
  // The plate sizes are those with fitted rows: a radius that only has zero-sinkage or unloading
  // rows says nothing about Kc/r + Kphi.
  std::map<double, double> fitted_max_force;
  for (const auto& p : d.points)
    if (p.fitted) fitted_max_force[p.radius] = std::max(fitted_max_force[p.radius], p.force);
  for (const auto& [r, f] : fitted_max_force) {
    if (!(f > 0))
      throw InputError(
          fmt::format("{}: every loading force of the plate of radius {} m is zero; the Bekker law needs a "
                      "positive force",
                      source, r));
    d.radii.push_back(r);
  }
  if (d.fitted_count() == 0)
    throw InputError(fmt::format("{}: no loading rows with sinkage > 0; nothing to fit the Bekker law to", source));
  const auto at_surface = std::count_if(d.points.begin(), d.points.end(), [](const PlatePoint& p) {
    return p.phase != PlatePhase::kUnload && p.sinkage == 0;
  });
  if (at_surface > 0)
    d.notes.push_back(
        fmt::format("{}: {} loading row(s) at sinkage 0, where the Bekker pressure is 0 whatever the "
                    "parameters: not fitted",
                    source, at_surface));
  return d;
}

ShearData make_shear_data(std::vector<ShearPoint> points, const std::string& source, const PointLocator& where) {
  ShearData d;
  d.path = source;
  const double torque_noise = kZeroNoise * largest_magnitude(points, &ShearPoint::torque);
  std::size_t at_rest = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    check_shear_point(points[i], i, where, torque_noise);
    if (!points[i].developed && points[i].angle == 0) {  // zero displacement: the torque model is 0
      ++at_rest;
      continue;
    }
    d.points.push_back(points[i]);
  }
  if (at_rest > 0)
    d.notes.push_back(
        fmt::format("{}: {} row(s) at shear angle 0, where the Janosi torque is 0 whatever the "
                    "parameters: not fitted",
                    source, at_rest));
  if (d.points.empty())
    throw InputError(fmt::format("{}: no rows with a shear angle > 0 or a developed torque", source));
  if (std::all_of(d.points.begin(), d.points.end(), [](const ShearPoint& p) { return p.torque == 0; }))
    throw InputError(fmt::format("{}: every torque is zero; nothing to fit the shear law to", source));
  return d;
}

PlateData load_plate_csv(const std::string& path) {
  const CsvTable t = CsvTable::read(path);
  t.require_columns({"plate_radius_m", "sinkage_m", "force_N"});
  std::vector<PlatePoint> points;
  for (std::size_t i = 0; i < t.rows(); ++i) {
    PlatePoint p;
    p.line = t.line_of(i);
    p.radius = t.number(i, "plate_radius_m");
    p.sinkage = t.number(i, "sinkage_m");
    p.force = t.number(i, "force_N");
    if (t.has_column("phase")) {
      const auto phase = parse_plate_phase(t.text(i, "phase"));
      if (!phase)
        throw InputError(fmt::format("{}: '{}' is not a phase; expected load, unload or reload (or empty)",
                                     t.where(i, "phase"), t.text(i, "phase")));
      p.phase = *phase;
    }
    points.push_back(p);
  }
  return make_plate_data(std::move(points), path, csv_locator(t));
}

ShearData load_shear_csv(const std::string& path) {
  const CsvTable t = CsvTable::read(path);
  t.require_columns({"inner_radius_m", "outer_radius_m", "normal_load_N", "angle_rad", "torque_Nm"});
  std::vector<ShearPoint> points;
  for (std::size_t i = 0; i < t.rows(); ++i) {
    ShearPoint p;
    p.line = t.line_of(i);
    p.inner_radius = t.number(i, "inner_radius_m");
    p.outer_radius = t.number(i, "outer_radius_m");
    p.normal_load = t.number(i, "normal_load_N");
    p.torque = t.number(i, "torque_Nm");
    const auto angle = t.optional_number(i, "angle_rad");
    p.developed = !angle.has_value();
    p.angle = angle.value_or(0.0);
    points.push_back(p);
  }
  return make_shear_data(std::move(points), path, csv_locator(t));
}

}  // namespace terracal::bayes
