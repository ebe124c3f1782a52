#include "core/vehicle/tmeasy_params.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <regex>
#include <set>
#include <stdexcept>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "core/json_file.hpp"
#include "core/json_object.hpp"
#include "core/range.hpp"
#include "core/text_check.hpp"

namespace terracal {
namespace {

using Json = nlohmann::json;

// One table of keys and ranges serves the three readers and validate(), so that they cannot disagree.
struct ScalarKey {
  const char* own;   // our key
  const char* lfdm;  // LFDM's key of the same meaning
  double TmeasyParams::*field;
  Range range;
};

const std::array<ScalarKey, 10>& scalar_keys() {
  static const std::array<ScalarKey, 10> keys = {{
      {"unloaded_radius", "r0", &TmeasyParams::unloaded_radius, {0, 10, true, false, "m"}},
      {"wheel_inertia", "jw", &TmeasyParams::wheel_inertia, {0, 1e5, true, false, "kg m^2"}},
      {"vertical_stiffness", "kt", &TmeasyParams::vertical_stiffness, {0, 1e10, true, false, "N/m"}},
      {"rolling_resistance", "rr", &TmeasyParams::rolling_resistance, {0, 1, false, false, ""}},
      {"nominal_load", "pn", &TmeasyParams::nominal_load, {0, 1e7, true, false, "N"}},
      {"max_load", "pnmax", &TmeasyParams::max_load, {0, 1e8, true, false, "N"}},
      {"longitudinal_stiffness", "cx", &TmeasyParams::longitudinal_stiffness, {0, 1e10, true, false, "N/m"}},
      {"lateral_stiffness", "cy", &TmeasyParams::lateral_stiffness, {0, 1e10, true, false, "N/m"}},
      // Zero damping would make tmeasy_relaxed divide 0 by 0 where the load, and with it the slip
      // stiffness, is zero.
      {"longitudinal_damping", "dx", &TmeasyParams::longitudinal_damping, {0, 1e8, true, false, "N s/m"}},
      {"lateral_damping", "dy", &TmeasyParams::lateral_damping, {0, 1e8, true, false, "N s/m"}},
  }};
  return keys;
}

constexpr Range kRdynRange{0, 1, false, false, ""};
// Inflation pressure in use over the one the load index holds at.
constexpr Range kPressureRatio{0, 10, true, false, ""};

// A curve's value; LFDM spells it head + x|y + tail + Pn|P2n ("dfx0Pn", "sysP2n").
struct CurveKey {
  const char* own;
  const char* head;
  const char* tail;
  double TmeasyCurve::*field;
  Range range;
};

const std::array<CurveKey, 5>& curve_keys() {
  static const std::array<CurveKey, 5> keys = {{
      {"df0", "df", "0", &TmeasyCurve::df0, {0, 1e9, true, false, "N"}},
      {"fm", "f", "m", &TmeasyCurve::fm, {0, 1e8, true, false, "N"}},
      {"sm", "s", "m", &TmeasyCurve::sm, {0, 10, true, false, ""}},
      {"fs", "f", "s", &TmeasyCurve::fs, {0, 1e8, true, false, "N"}},
      {"ss", "s", "s", &TmeasyCurve::ss, {0, 100, true, false, ""}},
  }};
  return keys;
}
const CurveKey& curve_key(const char* own) {
  for (const auto& k : curve_keys())
    if (std::string(k.own) == own) return k;
  throw std::logic_error("no TMeasy curve key " + std::string(own));
}

const char* const kDirection[2] = {"longitudinal", "lateral"};

// The curves of one direction. (Not `(dir == 0 ? p.x : p.y)[i].*field = v`: GCC 12 assigns that to
// a temporary copy of the array.)
TmeasyCurve* curves(TmeasyParams& p, int dir) { return dir == 0 ? &p.x[0] : &p.y[0]; }
const TmeasyCurve* curves(const TmeasyParams& p, int dir) { return dir == 0 ? &p.x[0] : &p.y[0]; }

// LFDM keys that carry no meaning here (see read_lfdm).
const char* const kLfdmIgnored[3] = {"step", "fzRdynco", "rdyncoCrit"};

// The names that messages give the values: the keys of the form the values were read from.
struct Names {
  bool lfdm = false;
  std::string scalar(const ScalarKey& k) const { return lfdm ? k.lfdm : k.own; }
  std::string scalar(const char* own) const {
    for (const auto& k : scalar_keys())
      if (std::string(k.own) == own) return scalar(k);
    throw std::logic_error(std::string("no TMeasy key ") + own);
  }
  std::string rdyn(int i) const {
    if (lfdm) return i == 0 ? "rdyncoPn" : "rdyncoP2n";
    return fmt::format("rdyn_coefficient[{}]", i);
  }
  std::string curve(int dir, const CurveKey& k, int i) const {
    if (lfdm) return std::string(k.head) + (dir == 0 ? "x" : "y") + k.tail + (i == 0 ? "Pn" : "P2n");
    return fmt::format("{}.{}[{}]", kDirection[dir], k.own, i);
  }
  std::string curve(int dir, const char* own, int i) const { return curve(dir, curve_key(own), i); }
};

[[noreturn]] void fail(const std::string& source, const std::string& key, const std::string& what) {
  throw InputError(fmt::format("{}: key '{}': {}", source, key, what));
}

std::string shown(const Json& v) { return shorten(v.dump()); }

std::set<std::string> lfdm_key_set() {
  std::set<std::string> s;
  const Names n{true};
  for (const auto& k : scalar_keys()) s.insert(k.lfdm);
  for (int i = 0; i < 2; ++i) s.insert(n.rdyn(i));
  for (int dir = 0; dir < 2; ++dir)
    for (const auto& k : curve_keys())
      for (int i = 0; i < 2; ++i) s.insert(n.curve(dir, k, i));
  for (const char* k : kLfdmIgnored) s.insert(k);
  return s;
}

std::set<std::string> own_key_set() {
  std::set<std::string> s = {"type", "rdyn_coefficient", "longitudinal", "lateral", "guess"};
  for (const auto& k : scalar_keys()) s.insert(k.own);
  return s;
}

// Like JsonObject::finish, but the message shows the value too (a misplaced value is easier to
// recognise than a misspelled key).
void refuse_unknown(const Json& j, const std::set<std::string>& allowed, const std::string& source,
                    const std::string& path, const std::string& why = "unknown key (misspelled, or not valid here)") {
  for (auto it = j.begin(); it != j.end(); ++it)
    if (!allowed.count(it.key()))
      fail(source, shorten(path.empty() ? it.key() : path + "." + it.key()),
           fmt::format("value {}: {}", shown(it.value()), why));
}

// [at Fzn, at 2 Fzn]
void read_pair(JsonObject& o, const std::string& key, const Range& r, double out[2]) {
  const Json& v = o.raw(key);
  if (!v.is_array() || v.size() != 2)
    o.fail(key, fmt::format("value {} is not an array of two numbers [at Fzn, at 2 Fzn]", shown(v)));
  for (int i = 0; i < 2; ++i) {
    const std::string ki = fmt::format("{}[{}]", key, i);
    if (!v[i].is_number()) o.fail(ki, fmt::format("value {} is not a number", shown(v[i])));
    const double x = v[i].get<double>();
    if (!(std::isfinite(x) && r.contains(x)))
      o.fail(ki, fmt::format("value {} is outside the allowed range {}", shown(v[i]), r.text()));
    out[i] = x;
  }
}

void require_type(JsonObject& o) {
  if (!o.has("type")) o.fail("type", "is required but missing: expected \"TMeasy\"");
  o.string_or("type", "", {"TMeasy"});
}

// --- the checks --------------------------------------------------------------------------------

// Rill's load interpolation of a force is F(q) = q (a - b q) with q = Fz / Fzn, a = 2 p1 - p2 / 2 and
// b = p1 - p2 / 2; of a slip s(q) = s1 + (s2 - s1) (q - 1). F / q and s are linear in q, so each is
// positive (and one exceeds another) over 0 < q <= q_max exactly when it is so at both ends.
double force_over_q(double q, double p1, double p2) { return (2.0 * p1 - 0.5 * p2) - (p1 - 0.5 * p2) * q; }

void check_curves_over_loads(const TmeasyParams& p, const std::string& source, const Names& n) {
  const double q_ends[2] = {0.0, p.max_load / p.nominal_load};
  auto load_text = [&](int e) {
    return e == 0 ? std::string("near zero load")
                  : fmt::format("at max_load ('{}') = {} N", n.scalar("max_load"), p.max_load);
  };
  for (int dir = 0; dir < 2; ++dir) {
    const TmeasyCurve* c = curves(p, dir);
    for (const char* f : {"df0", "fm", "fs"}) {
      const auto& k = curve_key(f);
      const double p1 = c[0].*k.field, p2 = c[1].*k.field;
      for (int e = 0; e < 2; ++e)
        if (!(force_over_q(q_ends[e], p1, p2) > 0.0))
          fail(source, n.curve(dir, k, 1),
               fmt::format("value {} with {} = {}: Rill's load interpolation F = q (2 F1 - F2/2 - (F1 - F2/2) q), "
                           "q = Fz / Fzn, is not positive {}; expected a positive force at every load up to "
                           "max_load",
                           p2, n.curve(dir, k, 0), p1, load_text(e)));
    }
    for (int e = 0; e < 2; ++e) {
      const double q = q_ends[e];
      const double fm = force_over_q(q, c[0].fm, c[1].fm), fs = force_over_q(q, c[0].fs, c[1].fs);
      if (fs > fm)
        fail(source, n.curve(dir, "fs", 1),
             fmt::format("value {} with {} = {}, {} = {} and {} = {} puts the sliding force above the maximum "
                         "force {} (fs / q = {:.6g} N, fm / q = {:.6g} N, q = Fz / Fzn); expected fs <= fm at every "
                         "load up to max_load",
                         c[1].fs, n.curve(dir, "fs", 0), c[0].fs, n.curve(dir, "fm", 0), c[0].fm, n.curve(dir, "fm", 1),
                         c[1].fm, load_text(e), fs, fm));
      const double sm = tmeasy_slip_at_load(q, c[0].sm, c[1].sm), ss = tmeasy_slip_at_load(q, c[0].ss, c[1].ss);
      if (!(sm > 0.0))
        fail(source, n.curve(dir, "sm", 1),
             fmt::format("value {} with {} = {} makes the slip at the maximum force (linear in the load) {:.6g} {}; "
                         "expected above 0 at every load up to max_load",
                         c[1].sm, n.curve(dir, "sm", 0), c[0].sm, sm, load_text(e)));
      if (!(ss > sm))
        fail(source, n.curve(dir, "ss", 1),
             fmt::format("value {} with {} = {} makes the sliding slip {:.6g} not above the slip at the maximum "
                         "force {:.6g} {}; expected sm < ss at every load up to max_load",
                         c[1].ss, n.curve(dir, "ss", 0), c[0].ss, ss, sm, load_text(e)));
    }
  }
}

void validate_named(const TmeasyParams& p, const std::string& source, const Names& n) {
  for (const auto& k : scalar_keys()) check_range(k.range, p.*k.field, n.scalar(k), source);
  for (int i = 0; i < 2; ++i) check_range(kRdynRange, p.rdyn_coefficient[i], n.rdyn(i), source);
  for (int dir = 0; dir < 2; ++dir)
    for (int i = 0; i < 2; ++i)
      for (const auto& k : curve_keys()) check_range(k.range, curves(p, dir)[i].*k.field, n.curve(dir, k, i), source);

  if (!(p.max_load > p.nominal_load))
    fail(source, n.scalar("max_load"),
         fmt::format("value {} must exceed {} = {} (loads beyond max_load use the curve at max_load)", p.max_load,
                     n.scalar("nominal_load"), p.nominal_load));
  if (!(p.max_load / p.vertical_stiffness < p.unloaded_radius))
    fail(
        source, n.scalar("max_load"),
        fmt::format("value {} presses the tire by {:.6g} m ({} = {} N/m), not less than {} = {} m; expected below "
                    "{:.6g} N",
                    p.max_load, p.max_load / p.vertical_stiffness, n.scalar("vertical_stiffness"), p.vertical_stiffness,
                    n.scalar("unloaded_radius"), p.unloaded_radius, p.unloaded_radius * p.vertical_stiffness));

  for (int dir = 0; dir < 2; ++dir) {
    for (int i = 0; i < 2; ++i) {
      const TmeasyCurve& c = curves(p, dir)[i];
      if (!(c.sm < c.ss))
        fail(source, n.curve(dir, "sm", i),
             fmt::format("value {} must be below {} = {}: the force peaks at sm before it slides from ss on", c.sm,
                         n.curve(dir, "ss", i), c.ss));
      if (!(c.fs <= c.fm))
        fail(source, n.curve(dir, "fs", i),
             fmt::format("value {} must not exceed {} = {}: the force falls from its maximum to the sliding force",
                         c.fs, n.curve(dir, "fm", i), c.fm));
      // The first segment F(s) = df0 s / (1 + σ (σ + a - 2)), σ = s / sm, a = df0 sm / fm, has
      // dF/dσ = fm a (1 - σ²) / (1 + (a - 2) σ + σ²)², and its denominator is (1 - σ)² + a σ > 0: it
      // rises monotonically to fm at sm for every a > 0, that is for any df0 > 0. Its force over slip,
      // df0 / (1 + σ (σ + a - 2)), falls with slip (the curve is concave at 0, F''(0) = -2 a (a - 2) fm /
      // sm²) only when a >= 2: df0 >= 2 fm / sm. Chrono (ChTMeasyTire::CheckParameters) refuses
      // smaller values, and Chrono's and LFDM's tmxy_combined raise df0 to 2 fm / sm; tmeasy.hpp uses
      // df0 as given, so we refuse, which keeps a file's meaning the same here as there.
      const double lowest = 2.0 * c.fm / c.sm;
      if (!(c.df0 >= lowest))
        fail(source, n.curve(dir, "df0", i),
             fmt::format("value {} is below 2 fm / sm = {} ({} = {}, {} = {}): the curve would start convex, its "
                         "force over slip rising with slip (Chrono and LFDM silently raise df0 to 2 fm / sm); "
                         "expected df0 >= {}",
                         c.df0, lowest, n.curve(dir, "fm", i), c.fm, n.curve(dir, "sm", i), c.sm, lowest));
    }
  }
  check_curves_over_loads(p, source, n);
}

// --- the forms ---------------------------------------------------------------------------------

TmeasyParams read_own(const Json& j, const std::string& source) {
  // Unknown keys first: a misspelled key is better named as such than as the right one missing.
  std::set<std::string> allowed = own_key_set();
  allowed.erase("guess");
  refuse_unknown(j, allowed, source, "");
  std::set<std::string> curve_allowed;
  for (const auto& k : curve_keys()) curve_allowed.insert(k.own);
  for (const char* dir : kDirection)
    if (j.contains(dir) && j[dir].is_object()) refuse_unknown(j[dir], curve_allowed, source, dir);

  JsonObject o(j, source, "");
  require_type(o);
  TmeasyParams p;
  for (const auto& k : scalar_keys()) p.*k.field = o.number(k.own, k.range);
  read_pair(o, "rdyn_coefficient", kRdynRange, p.rdyn_coefficient);
  for (int dir = 0; dir < 2; ++dir) {
    JsonObject c = o.object(kDirection[dir]);
    TmeasyCurve* curve = curves(p, dir);
    for (const auto& k : curve_keys()) {
      double v[2];
      read_pair(c, k.own, k.range, v);
      curve[0].*k.field = v[0];
      curve[1].*k.field = v[1];
    }
    c.finish();
  }
  o.finish();
  validate_named(p, source, Names{false});
  return p;
}

TmeasyParams read_lfdm(const Json& j, const std::string& source) {
  refuse_unknown(j, lfdm_key_set(), source, "");
  JsonObject o(j, source, "");
  const Names n{true};
  TmeasyParams p;
  for (const auto& k : scalar_keys()) p.*k.field = o.number(k.lfdm, k.range);
  for (int i = 0; i < 2; ++i) p.rdyn_coefficient[i] = o.number(n.rdyn(i), kRdynRange);
  for (int dir = 0; dir < 2; ++dir)
    for (const auto& k : curve_keys())
      for (int i = 0; i < 2; ++i) curves(p, dir)[i].*k.field = o.number(n.curve(dir, k, i), k.range);
  // Keys of LFDM's file that have no meaning here; each must still be a number, as LFDM reads it so.
  //   step: LFDM's integration step. Ours is a command-line option of the run, not a tire property.
  //   fzRdynco, rdyncoCrit: LFDM's tireInit overwrites both before use with values computed from pn,
  //     rdyncoPn and rdyncoP2n (the load where rdyn is least, and the weighting there), so what a file
  //     says never reaches its model. (LFDM and Chrono do freeze the weighting at that load beyond it;
  //     tmeasy_at_load keeps it linear in the load. That is a matter of the model, not of the file.)
  const double big = std::numeric_limits<double>::max();
  o.number_or("step", 0, Range{0, 10, true, false, "s"});
  o.number_or("fzRdynco", 0, -big, big);
  o.number_or("rdyncoCrit", 0, -big, big);
  o.finish();
  validate_named(p, source, n);
  return p;
}

TmeasyParams read_guess(const Json& j, const std::string& source) {
  JsonObject o(j, source, "");
  require_type(o);
  for (auto it = j.begin(); it != j.end(); ++it)
    if (it.key() != "type" && it.key() != "guess" && it.key() != "wheel_inertia")
      fail(source, shorten(it.key()),
           fmt::format("value {} is not valid beside 'guess', which derives every parameter but wheel_inertia; "
                       "give either 'guess' and 'wheel_inertia' or the full parameter set",
                       shown(it.value())));
  if (!o.has("wheel_inertia"))
    o.fail("wheel_inertia", "is required beside 'guess' (Chrono's guess does not estimate the wheel's inertia)");
  const Range inertia_range = scalar_keys()[1].range;
  const double inertia = o.number("wheel_inertia", inertia_range);
  JsonObject g = o.object("guess");
  refuse_unknown(
      o.raw("guess"),
      {"tire_size", "load_index", "max_load", "vehicle_type", "tire_mass", "inflation_pressure", "rated_pressure"},
      source, "guess");

  if (!g.has("tire_size")) g.fail("tire_size", "is required but missing (\"255/50R19\" or \"37x12.5R16.5\")");
  const std::string size_text = g.string_or("tire_size", "", {});
  const TireSize size = parse_tire_size(size_text, source, g.key_path("tire_size"));

  if (g.has("load_index") == g.has("max_load"))
    g.fail("load_index", g.has("load_index") ? "and 'guess.max_load' are both given; give one of them"
                                             : "or 'guess.max_load' is required (the tire's largest load)");
  const double max_load = g.has("load_index") ? tire_max_load(int(g.integer_or("load_index", 0, 0, 279)))
                                              : g.number("max_load", Range{0, 2e7, true, false, "N"});

  if (!g.has("vehicle_type")) g.fail("vehicle_type", "is required but missing: expected truck or passenger");
  const bool truck = g.string_or("vehicle_type", "", {"truck", "passenger"}) == "truck";
  if (!g.has("tire_mass"))
    g.fail("tire_mass", "is required but missing (Chrono's guess takes the tread damping from it) [kg]");
  const double tire_mass = g.number("tire_mass", Range{0, 1e4, true, false, "kg"});

  double pressure_ratio = 1.0;
  if (g.has("inflation_pressure") != g.has("rated_pressure"))
    g.fail(g.has("inflation_pressure") ? "rated_pressure" : "inflation_pressure",
           "is required beside the other pressure: the guess scales the load by (inflation_pressure / "
           "rated_pressure)^0.8");
  if (g.has("inflation_pressure")) {
    const Range pressure{0, 1e8, true, false, "Pa"};
    const double use = g.number("inflation_pressure", pressure), rated = g.number("rated_pressure", pressure);
    pressure_ratio = use / rated;
    if (!kPressureRatio.contains(pressure_ratio))
      g.fail("inflation_pressure", fmt::format("value {} is {:.6g} times rated_pressure = {}; expected a ratio in {}",
                                               use, pressure_ratio, rated, kPressureRatio.text()));
  }
  g.finish();
  o.finish();
  try {
    return tmeasy_guess(max_load, size.width, size.aspect_ratio, size.rim_diameter, truck, tire_mass, inertia,
                        pressure_ratio);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: 'guess': {}", source, e.what()));
  }
}

// Chrono's normalised curves for the guess (ChTMeasyTire::GuessTruck80Par, GuessPassCar70Par): forces
// per unit load, at Fzn and 2 Fzn.
struct GuessCurve {
  double df0[2], fm[2], sm[2], fs[2], ss[2];
};
constexpr GuessCurve kTruckX{{17.6866, 13.8046}, {0.88468, 0.7479}, {0.12, 0.15}, {0.54397, 0.50365}, {0.9, 0.95}};
constexpr GuessCurve kTruckY{
    {5.948, 5.506}, {0.77253, 0.73048}, {0.38786, 0.38786}, {0.71139, 0.66823}, {0.82534, 0.91309}};
constexpr GuessCurve kCarX{{18.6758, 20.1757}, {1.1205, 1.072}, {0.17, 0.15}, {0.8766, 0.8245}, {0.9, 0.95}};
constexpr GuessCurve kCarY{
    {14.9858, 10.0505}, {1.0084, 0.90003}, {0.18197, 0.24472}, {0.83941, 0.76782}, {0.82534, 0.91309}};

void set_guess_curve(TmeasyCurve c[2], const GuessCurve& g, double fzn) {
  for (int i = 0; i < 2; ++i) {
    const double load = (i + 1) * fzn;
    c[i].df0 = g.df0[i] * load;
    c[i].fm = g.fm[i] * load;
    c[i].fs = g.fs[i] * load;
    c[i].sm = g.sm[i];
    c[i].ss = g.ss[i];
  }
}

// ISO 4000-1 / ETRTO load index -> load capacity [kg], LI 0 to 279. The series repeats tenfold every
// 80 indices (LI 41 = 145 kg, LI 121 = 1450 kg, LI 201 = 14500 kg). Chrono's table has 46.5, 5850 and
// 15550 kg at LI 1, 169 and 203, where the series has 46.2, 5800 and 15500.
// clang-format off
constexpr std::array<double, 280> kLoadIndexKg = {
    /* LI   0 */     45,   46.2,   47.5,   48.7,     50,   51.5,     53,   54.5,     56,     58,
    /* LI  10 */     60,   61.5,     63,     65,     67,     69,     71,     73,     75,   77.5,
    /* LI  20 */     80,   82.5,     85,   87.5,     90,   92.5,     95,   97.5,    100,    103,
    /* LI  30 */    106,    109,    112,    115,    118,    121,    125,    128,    132,    136,
    /* LI  40 */    140,    145,    150,    155,    160,    165,    170,    175,    180,    185,
    /* LI  50 */    190,    195,    200,    206,    212,    218,    224,    230,    236,    243,
    /* LI  60 */    250,    257,    265,    272,    280,    290,    300,    307,    315,    325,
    /* LI  70 */    335,    345,    355,    365,    375,    387,    400,    412,    425,    437,
    /* LI  80 */    450,    462,    475,    487,    500,    515,    530,    545,    560,    580,
    /* LI  90 */    600,    615,    630,    650,    670,    690,    710,    730,    750,    775,
    /* LI 100 */    800,    825,    850,    875,    900,    925,    950,    975,   1000,   1030,
    /* LI 110 */   1060,   1090,   1120,   1150,   1180,   1215,   1250,   1285,   1320,   1360,
    /* LI 120 */   1400,   1450,   1500,   1550,   1600,   1650,   1700,   1750,   1800,   1850,
    /* LI 130 */   1900,   1950,   2000,   2060,   2120,   2180,   2240,   2300,   2360,   2430,
    /* LI 140 */   2500,   2575,   2650,   2725,   2800,   2900,   3000,   3075,   3150,   3250,
    /* LI 150 */   3350,   3450,   3550,   3650,   3750,   3875,   4000,   4125,   4250,   4375,
    /* LI 160 */   4500,   4625,   4750,   4875,   5000,   5150,   5300,   5450,   5600,   5800,
    /* LI 170 */   6000,   6150,   6300,   6500,   6700,   6900,   7100,   7300,   7500,   7750,
    /* LI 180 */   8000,   8250,   8500,   8750,   9000,   9250,   9500,   9750,  10000,  10300,
    /* LI 190 */  10600,  10900,  11200,  11500,  11800,  12150,  12500,  12850,  13200,  13600,
    /* LI 200 */  14000,  14500,  15000,  15500,  16000,  16500,  17000,  17500,  18000,  18500,
    /* LI 210 */  19000,  19500,  20000,  20600,  21200,  21800,  22400,  23000,  23600,  24300,
    /* LI 220 */  25000,  25750,  26500,  27250,  28000,  29000,  30000,  30750,  31500,  32500,
    /* LI 230 */  33500,  34500,  35500,  36500,  37500,  38750,  40000,  41250,  42500,  43750,
    /* LI 240 */  45000,  46250,  47500,  48750,  50000,  51500,  53000,  54500,  56000,  58000,
    /* LI 250 */  60000,  61500,  63000,  65000,  67000,  69000,  71000,  73000,  75000,  77500,
    /* LI 260 */  80000,  82500,  85000,  87500,  90000,  92500,  95000,  97500, 100000, 103000,
    /* LI 270 */ 106000, 109000, 112000, 115000, 118000, 121000, 125000, 128500, 132000, 136000
};
// clang-format on

}  // namespace

// --- public ------------------------------------------------------------------------------------

void validate(const TmeasyParams& p, const std::string& source) { validate_named(p, source, Names{false}); }

TmeasyParams read_tmeasy(const nlohmann::json& j, const std::string& source) {
  if (!j.is_object())
    throw InputError(fmt::format("{}: a TMeasy tire must be a JSON object, got {}", source, shown(j)));
  static const std::set<std::string> lfdm = lfdm_key_set(), own = own_key_set();
  const Json::const_iterator none = j.end();
  Json::const_iterator lfdm_key = none, own_key = none;
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (lfdm_key == none && lfdm.count(it.key())) lfdm_key = it;
    if (own_key == none && own.count(it.key())) own_key = it;
  }
  if (lfdm_key != none && own_key != none)
    throw InputError(fmt::format(
        "{}: key '{}' (value {}) is LFDM's and key '{}' (value {}) is ours: a tire file takes one form, LFDM's "
        "keys (r0, pn, dfx0Pn, ...) or ours (\"type\": \"TMeasy\", unloaded_radius, nominal_load, ...)",
        source, lfdm_key.key(), shown(lfdm_key.value()), own_key.key(), shown(own_key.value())));
  if (lfdm_key != none) return read_lfdm(j, source);
  if (own_key == none) {
    const std::string first = j.empty() ? "none" : fmt::format("'{}'", shorten(j.begin().key()));
    throw InputError(
        fmt::format("{}: not a TMeasy tire: expected \"type\": \"TMeasy\" with our keys, or LFDM's keys (r0, pn, ...); "
                    "first key found: {}",
                    source, first));
  }
  return j.contains("guess") ? read_guess(j, source) : read_own(j, source);
}

TmeasyParams read_tmeasy_file(const std::string& path) {
  return read_tmeasy(read_json_file(path, "TMeasy tire file"), path);
}

nlohmann::json tmeasy_json(const TmeasyParams& p) {
  Json j;
  j["type"] = "TMeasy";
  for (const auto& k : scalar_keys()) j[k.own] = p.*k.field;
  j["rdyn_coefficient"] = {p.rdyn_coefficient[0], p.rdyn_coefficient[1]};
  for (int dir = 0; dir < 2; ++dir) {
    const TmeasyCurve* c = curves(p, dir);
    Json cj;
    for (const auto& k : curve_keys()) cj[k.own] = {c[0].*k.field, c[1].*k.field};
    j[kDirection[dir]] = cj;
  }
  return j;
}

TireSize parse_tire_size(const std::string& text, const std::string& where, const std::string& key) {
  // Metric: P255/50R19, LT265/75R16, 315/80R22.5, 215/65R16C. Flotation: 37x12.5R16.5, 33x12.50R15LT.
  static const std::regex metric(R"(^(P|LT)?([0-9]{3})/([0-9]{2})(ZR|R|D|B|-)([0-9]{2}(\.[0-9])?)C?$)");
  static const std::regex flotation(
      R"(^([0-9]{2}(\.[0-9]+)?)[xX]([0-9]{1,2}(\.[0-9]+)?)(ZR|R|D|B|-)([0-9]{2}(\.[0-9]+)?)(LT)?$)");
  constexpr double inch = 0.0254;
  const std::string prefix = where.empty() ? "" : where + ": ";
  auto refuse = [&](const std::string& why) {
    throw InputError(fmt::format("{}key '{}': value {} {}", prefix, key, excerpt(text), why));
  };
  std::smatch m;
  TireSize s;
  if (std::regex_match(text, m, metric)) {
    s.width = std::stod(m[2].str()) * 1e-3;
    s.aspect_ratio = std::stod(m[3].str()) * 1e-2;
    s.rim_diameter = std::stod(m[5].str()) * inch;
    if (!(s.aspect_ratio > 0) || !(s.width > 0) || !(s.rim_diameter > 0))
      refuse("has a zero width, aspect ratio or rim diameter");
    return s;
  }
  if (std::regex_match(text, m, flotation)) {
    const double diameter = std::stod(m[1].str()) * inch;
    s.width = std::stod(m[3].str()) * inch;
    s.rim_diameter = std::stod(m[6].str()) * inch;
    if (!(s.width > 0) || !(s.rim_diameter > 0)) refuse("has a zero width or rim diameter");
    if (!(diameter > s.rim_diameter))
      refuse(fmt::format("has an overall diameter ({} in) not above its rim's ({} in)", m[1].str(), m[6].str()));
    s.aspect_ratio = 0.5 * (diameter - s.rim_diameter) / s.width;
    return s;
  }
  refuse(
      "is not a tire size; expected metric WIDTH/RATIO R RIM (\"255/50R19\": mm, %, inches; P or LT in front, "
      "R, ZR, D, B or -) or flotation DIAMETER x WIDTH R RIM (\"37x12.5R16.5\": inches)");
  return s;  // not reached
}

double tire_max_load(int load_index) {
  if (load_index < 0 || load_index >= int(kLoadIndexKg.size()))
    throw InputError(fmt::format("key 'load_index': value {} is outside the allowed range [0, {}]", load_index,
                                 kLoadIndexKg.size() - 1));
  return kLoadIndexKg[std::size_t(load_index)] * 9.81;
}

// Chrono's ChTMeasyTire::GuessTruck80Par / GuessPassCar70Par as of the Chrono 7 era
// (projectchrono/chrono src/chrono_vehicle/wheeled_vehicle/tire/ChTMeasyTire.cpp): the version that
// sets every parameter TmeasyParams holds (tread stiffness and damping, the rdyn weighting) and whose
// curves are those of Chrono's HMMWV TMeasy data, which LFDM's TMeasy.json copies. Later Chrono
// (9.x) fits other curves and no longer guesses the tread or rdyn.
TmeasyParams tmeasy_guess(double max_load, double width, double ratio, double rim_diameter, bool truck,
                          double tire_mass, double wheel_inertia, double pressure_ratio) {
  check_range(Range{0, 2e7, true, false, "N"}, max_load, "max_load");
  check_range(Range{0, 5, true, false, "m"}, width, "width");
  check_range(Range{0, 2, true, false, ""}, ratio, "ratio");
  check_range(Range{0, 5, true, false, "m"}, rim_diameter, "rim_diameter");
  check_range(Range{0, 1e4, true, false, "kg"}, tire_mass, "tire_mass");
  check_range(scalar_keys()[1].range, wheel_inertia, "wheel_inertia");
  check_range(kPressureRatio, pressure_ratio, "pressure_ratio");

  const double section_height = width * ratio;
  const double deflection_at_max_load = 0.16 * section_height;
  const double damping_ratio = 0.5;
  TmeasyParams p;
  p.unloaded_radius = section_height + 0.5 * rim_diameter;
  p.wheel_inertia = wheel_inertia;
  p.nominal_load = 0.5 * max_load * std::pow(pressure_ratio, 0.8);
  p.max_load = 3.5 * p.nominal_load;
  p.vertical_stiffness = max_load / deflection_at_max_load;
  p.rolling_resistance = 0.015;
  p.longitudinal_stiffness = 0.9 * p.vertical_stiffness;
  p.lateral_stiffness = 0.8 * p.vertical_stiffness;
  p.longitudinal_damping = damping_ratio * std::sqrt(p.longitudinal_stiffness * tire_mass);
  p.lateral_damping = damping_ratio * std::sqrt(p.lateral_stiffness * tire_mass);
  p.rdyn_coefficient[0] = 0.375;
  p.rdyn_coefficient[1] = 0.75;
  set_guess_curve(p.x, truck ? kTruckX : kCarX, p.nominal_load);
  set_guess_curve(p.y, truck ? kTruckY : kCarY, p.nominal_load);
  validate(p, "the guessed parameters");
  return p;
}

}  // namespace terracal
