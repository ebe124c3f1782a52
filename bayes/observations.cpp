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

void require_positive(const CsvTable& t, std::size_t row, const std::string& col, double v) {
  if (!(v > 0)) throw InputError(fmt::format("{}: {} must be > 0", t.where(row, col), v));
}

void reject_millimetres(const CsvTable& t, std::size_t row, const std::string& col, double v, double limit,
                        const char* what) {
  if (v > limit)
    throw InputError(fmt::format("{}: {} = {} m is implausible for a bevameter {} (expected at most {} m); "
                                 "the file looks like it is in millimetres: convert to metres",
                                 t.where(row, col), col, v, what, limit));
}

// A curve starts at about zero and, simulated or measured, can dip a hair below it: that is noise,
// not a sign error. A value below -kZeroNoise x the largest magnitude of its column is refused.
constexpr double kZeroNoise = 0.02;

double largest_magnitude(const CsvTable& t, const std::string& col) {
  double m = 0;
  for (std::size_t i = 0; i < t.rows(); ++i) m = std::max(m, std::abs(t.number(i, col)));
  return m;
}

PlatePhase parse_phase(const CsvTable& t, std::size_t row) {
  const std::string s = t.text(row, "phase");
  if (s.empty() || s == "load") return PlatePhase::kLoad;
  if (s == "unload") return PlatePhase::kUnload;
  if (s == "reload") return PlatePhase::kReload;
  throw InputError(fmt::format("{}: '{}' is not a phase; expected load, unload or reload (or empty)", t.where(row, "phase"), s));
}

}  // namespace

int PlateData::fitted_count() const {
  return static_cast<int>(std::count_if(points.begin(), points.end(), [](const PlatePoint& p) { return p.fitted; }));
}

PlateData load_plate_csv(const std::string& path) {
  const CsvTable t = CsvTable::read(path);
  t.require_columns({"plate_radius_m", "sinkage_m", "force_N"});
  PlateData d;
  d.path = path;
  std::map<double, double> max_sinkage;  // per plate radius: the deepest sinkage so far
  std::map<double, double> max_force;    // per plate radius: the largest force so far
  std::map<double, bool> rejoined;       // per plate radius: this reload is back on the virgin curve
  const double force_noise = kZeroNoise * largest_magnitude(t, "force_N");
  for (std::size_t i = 0; i < t.rows(); ++i) {
    PlatePoint p;
    p.line = t.line_of(i);
    p.radius = t.number(i, "plate_radius_m");
    p.sinkage = t.number(i, "sinkage_m");
    p.force = t.number(i, "force_N");
    p.phase = t.has_column("phase") ? parse_phase(t, i) : PlatePhase::kLoad;
    require_positive(t, i, "plate_radius_m", p.radius);
    if (p.sinkage < 0) throw InputError(fmt::format("{}: sinkage {} m is negative; expected >= 0", t.where(i, "sinkage_m"), p.sinkage));
    if (p.force < -force_noise)
      throw InputError(fmt::format("{}: force {} N is negative; a plate pushed into soil meets a force >= 0 (values down to "
                                   "-{} % of the largest force, {} N, pass as noise; remove the sensor offset, or check the "
                                   "sign convention)", t.where(i, "force_N"), p.force, 100 * kZeroNoise, force_noise));
    reject_millimetres(t, i, "plate_radius_m", p.radius, kMaxPlausibleRadius, "plate radius");
    reject_millimetres(t, i, "sinkage_m", p.sinkage, kMaxPlausibleSinkage, "plate sinkage");
    // The Bekker law describes loading beyond the deepest sinkage so far (virgin loading).
    double& deepest = max_sinkage[p.radius];
    // Unloading raises the plate: a deeper unload row contradicts its label, and the elastic
    // stiffness would be fitted to a virgin-loading point.
    if (p.phase == PlatePhase::kUnload && p.sinkage > deepest)
      throw InputError(fmt::format("{}: unload row at sinkage {} m is deeper than the deepest sinkage so far of the plate "
                                   "r = {} m ({} m); expected at most {} m (is the phase column right?)",
                                   t.where(i, "sinkage_m"), p.sinkage, p.radius, deepest, deepest));
    // A reload first climbs its elastic branch (in SCM up the unload line to the old deepest
    // point); it is back on the virgin curve once its force passes the largest force so far.
    // Once there it stays there until the next unload: a noisy force (a CRM curve) that dips below
    // the old largest force is still virgin loading, not a new elastic branch of one row.
    double& strongest = max_force[p.radius];
    bool& back_on_virgin = rejoined[p.radius];
    if (p.phase == PlatePhase::kUnload) back_on_virgin = false;
    p.fitted = p.phase != PlatePhase::kUnload && p.sinkage > 0 && p.sinkage > deepest &&
               (p.phase != PlatePhase::kReload || back_on_virgin || p.force >= strongest);
    if (p.phase == PlatePhase::kReload && p.fitted) back_on_virgin = true;
    deepest = std::max(deepest, p.sinkage);
    if (p.phase != PlatePhase::kReload || p.fitted) strongest = std::max(strongest, p.force);
    d.points.push_back(p);
  }
  // The plate sizes are those with fitted rows: a radius that only has zero-sinkage or unloading
  // rows says nothing about Kc/r + Kphi.
  std::map<double, double> fitted_max_force;
  for (const auto& p : d.points)
    if (p.fitted) fitted_max_force[p.radius] = std::max(fitted_max_force[p.radius], p.force);
  for (const auto& [r, f] : fitted_max_force) {
    if (!(f > 0))
      throw InputError(fmt::format("{}: every loading force of the plate of radius {} m is zero; the Bekker law needs a "
                                   "positive force", path, r));
    d.radii.push_back(r);
  }
  if (d.fitted_count() == 0)
    throw InputError(fmt::format("{}: no loading rows with sinkage > 0; nothing to fit the Bekker law to", path));
  return d;
}

ShearData load_shear_csv(const std::string& path) {
  const CsvTable t = CsvTable::read(path);
  t.require_columns({"inner_radius_m", "outer_radius_m", "normal_load_N", "angle_rad", "torque_Nm"});
  ShearData d;
  d.path = path;
  const double torque_noise = kZeroNoise * largest_magnitude(t, "torque_Nm");
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
    if (p.inner_radius < 0)
      throw InputError(fmt::format("{}: {} m is negative; expected >= 0", t.where(i, "inner_radius_m"), p.inner_radius));
    require_positive(t, i, "outer_radius_m", p.outer_radius);
    if (p.outer_radius <= p.inner_radius)
      throw InputError(fmt::format("{}: outer radius {} m must exceed the inner radius {} m", t.where(i, "outer_radius_m"),
                                   p.outer_radius, p.inner_radius));
    reject_millimetres(t, i, "outer_radius_m", p.outer_radius, kMaxPlausibleRadius, "annulus radius");
    require_positive(t, i, "normal_load_N", p.normal_load);
    if (p.torque < -torque_noise)
      throw InputError(fmt::format("{}: torque {} N m is negative; expected >= 0 (values down to -{} % of the largest torque, "
                                   "{} N m, pass as noise; check the sign convention)", t.where(i, "torque_Nm"), p.torque,
                                   100 * kZeroNoise, torque_noise));
    if (p.angle < 0)
      throw InputError(fmt::format("{}: shear angle {} rad is negative; expected >= 0 (or empty for the developed torque)",
                                   t.where(i, "angle_rad"), p.angle));
    if (!p.developed && p.angle == 0) continue;  // zero displacement carries no information (torque model is 0)
    d.points.push_back(p);
  }
  if (d.points.empty()) throw InputError(fmt::format("{}: no rows with a shear angle > 0 or a developed torque", path));
  if (std::all_of(d.points.begin(), d.points.end(), [](const ShearPoint& p) { return p.torque == 0; }))
    throw InputError(fmt::format("{}: every torque is zero; nothing to fit the shear law to", path));
  return d;
}

}  // namespace terracal::bayes
