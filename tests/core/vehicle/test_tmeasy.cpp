// The TMeasy tire (core/vehicle/tmeasy.hpp) on LFDM's HMMWV tire, and its parameter files
// (core/vehicle/tmeasy_params.hpp): LFDM's form, ours and Chrono's engineer's guess, and the refusals.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "../../scratch_dir.hpp"
#include "core/errors.hpp"
#include "core/vehicle/tmeasy.hpp"
#include "core/vehicle/tmeasy_params.hpp"

using namespace terracal;
using Catch::Matchers::Contains;
using Json = nlohmann::json;

namespace {

// uwsbel/low-fidelity-dynamic-models, wheeled_vehicle_models/18dof/data/json/TMeasy.json, as published.
// Its curves, loads and vertical stiffness are those of Chrono's HMMWV TMeasy tire
// (data/vehicle/hmmwv/tire/HMMWV_TMeasyTire.json).
const char* const kLfdmHmmwv = R"({
    "jw" : 6.5,
    "rr" : 0.015,
    "r0" : 0.4699,
    "pn" : 8562.8266,
    "pnmax" : 29969.893,
    "cx" : 185004.42,
    "cy" : 164448.37,
    "kt" : 411121.0,
    "dx" : 3700,
    "dy" : 3488,
    "rdyncoPn" : 0.375,
    "rdyncoP2n" : 0.75,
    "fzRdynco" : 0,
    "rdyncoCrit" : 0,
    "dfx0Pn" : 151447.2,
    "dfx0P2n" : 236412.79,
    "fxmPn" : 7575.3614,
    "fxmP2n" : 12808.276,
    "fxsPn" : 4657.9208,
    "fxsP2n" : 8625.3352,
    "sxmPn" : 0.12,
    "sxmP2n" : 0.15,
    "sxsPn" : 0.9,
    "sxsP2n" : 0.95,
    "dfy0Pn" : 50931.693,
    "dfy0P2n" : 94293.84,
    "fymPn" : 6615.0404,
    "fymP2n" : 12509.947,
    "fysPn" : 6091.5092,
    "fysP2n" : 11443.875,
    "symPn" : 0.38786,
    "symP2n" : 0.38786,
    "sysPn" : 0.82534,
    "sysP2n" : 0.91309,
    "step" : 0.001
})";

Json lfdm_hmmwv_json() { return Json::parse(kLfdmHmmwv); }
TmeasyParams hmmwv() { return read_tmeasy(lfdm_hmmwv_json(), "TMeasy.json"); }

// The InputError's message, or "" when there is none.
std::string error_of(const Json& j) {
  try {
    read_tmeasy(j, "t.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}
std::string validate_error(const TmeasyParams& p) {
  try {
    validate(p, "built");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

struct Force {
  double fx = 0, fy = 0;
};
Force steady(const TmeasyParams& p, double fz, double sx, double sy) {
  const TmeasyLoadState st = tmeasy_at_load(p, fz);
  const TmeasyStiffness k = tmeasy_steady_stiffness(st, sx, sy, fz);
  return {k.kx * sx, k.ky * sy};
}

// Every value, with our key and LFDM's.
struct Field {
  const char* own;
  const char* lfdm;
  double* (*at)(TmeasyParams&);
};
std::vector<Field> fields() {
  return {
      {"unloaded_radius", "r0", [](TmeasyParams& p) { return &p.unloaded_radius; }},
      {"wheel_inertia", "jw", [](TmeasyParams& p) { return &p.wheel_inertia; }},
      {"vertical_stiffness", "kt", [](TmeasyParams& p) { return &p.vertical_stiffness; }},
      {"rolling_resistance", "rr", [](TmeasyParams& p) { return &p.rolling_resistance; }},
      {"nominal_load", "pn", [](TmeasyParams& p) { return &p.nominal_load; }},
      {"max_load", "pnmax", [](TmeasyParams& p) { return &p.max_load; }},
      {"longitudinal_stiffness", "cx", [](TmeasyParams& p) { return &p.longitudinal_stiffness; }},
      {"lateral_stiffness", "cy", [](TmeasyParams& p) { return &p.lateral_stiffness; }},
      {"longitudinal_damping", "dx", [](TmeasyParams& p) { return &p.longitudinal_damping; }},
      {"lateral_damping", "dy", [](TmeasyParams& p) { return &p.lateral_damping; }},
      {"rdyn_coefficient[0]", "rdyncoPn", [](TmeasyParams& p) { return &p.rdyn_coefficient[0]; }},
      {"rdyn_coefficient[1]", "rdyncoP2n", [](TmeasyParams& p) { return &p.rdyn_coefficient[1]; }},
      {"longitudinal.df0[0]", "dfx0Pn", [](TmeasyParams& p) { return &p.x[0].df0; }},
      {"longitudinal.df0[1]", "dfx0P2n", [](TmeasyParams& p) { return &p.x[1].df0; }},
      {"longitudinal.fm[0]", "fxmPn", [](TmeasyParams& p) { return &p.x[0].fm; }},
      {"longitudinal.fm[1]", "fxmP2n", [](TmeasyParams& p) { return &p.x[1].fm; }},
      {"longitudinal.sm[0]", "sxmPn", [](TmeasyParams& p) { return &p.x[0].sm; }},
      {"longitudinal.sm[1]", "sxmP2n", [](TmeasyParams& p) { return &p.x[1].sm; }},
      {"longitudinal.fs[0]", "fxsPn", [](TmeasyParams& p) { return &p.x[0].fs; }},
      {"longitudinal.fs[1]", "fxsP2n", [](TmeasyParams& p) { return &p.x[1].fs; }},
      {"longitudinal.ss[0]", "sxsPn", [](TmeasyParams& p) { return &p.x[0].ss; }},
      {"longitudinal.ss[1]", "sxsP2n", [](TmeasyParams& p) { return &p.x[1].ss; }},
      {"lateral.df0[0]", "dfy0Pn", [](TmeasyParams& p) { return &p.y[0].df0; }},
      {"lateral.df0[1]", "dfy0P2n", [](TmeasyParams& p) { return &p.y[1].df0; }},
      {"lateral.fm[0]", "fymPn", [](TmeasyParams& p) { return &p.y[0].fm; }},
      {"lateral.fm[1]", "fymP2n", [](TmeasyParams& p) { return &p.y[1].fm; }},
      {"lateral.sm[0]", "symPn", [](TmeasyParams& p) { return &p.y[0].sm; }},
      {"lateral.sm[1]", "symP2n", [](TmeasyParams& p) { return &p.y[1].sm; }},
      {"lateral.fs[0]", "fysPn", [](TmeasyParams& p) { return &p.y[0].fs; }},
      {"lateral.fs[1]", "fysP2n", [](TmeasyParams& p) { return &p.y[1].fs; }},
      {"lateral.ss[0]", "sysPn", [](TmeasyParams& p) { return &p.y[0].ss; }},
      {"lateral.ss[1]", "sysP2n", [](TmeasyParams& p) { return &p.y[1].ss; }},
  };
}

// Our JSON's place of a key "a.b[i]".
Json& own_slot(Json& j, const std::string& key) {
  std::string k = key;
  Json* at = &j;
  const auto dot = k.find('.');
  if (dot != std::string::npos) {
    at = &(*at)[k.substr(0, dot)];
    k = k.substr(dot + 1);
  }
  const auto bracket = k.find('[');
  if (bracket == std::string::npos) return (*at)[k];
  return (*at)[k.substr(0, bracket)][std::size_t(k[bracket + 1] - '0')];
}

constexpr double kInch = 0.0254;

}  // namespace

TEST_CASE("TMeasy: LFDM's HMMWV tire file loads, each value where ours keeps it", "[tmeasy]") {
  test::ScratchDir dir("tmeasy_lfdm");
  const std::string path = (dir.path / "TMeasy.json").string();
  std::ofstream(path) << kLfdmHmmwv;
  TmeasyParams p = read_tmeasy_file(path);
  CHECK(p.wheel_inertia == 6.5);
  CHECK(p.rolling_resistance == 0.015);
  CHECK(p.unloaded_radius == 0.4699);
  CHECK(p.nominal_load == 8562.8266);
  CHECK(p.max_load == 29969.893);
  CHECK(p.longitudinal_stiffness == 185004.42);
  CHECK(p.lateral_stiffness == 164448.37);
  CHECK(p.vertical_stiffness == 411121.0);
  CHECK(p.longitudinal_damping == 3700);
  CHECK(p.lateral_damping == 3488);
  CHECK(p.rdyn_coefficient[0] == 0.375);
  CHECK(p.rdyn_coefficient[1] == 0.75);
  CHECK(p.x[0].df0 == 151447.2);
  CHECK(p.x[1].df0 == 236412.79);
  CHECK(p.x[0].fm == 7575.3614);
  CHECK(p.x[1].fm == 12808.276);
  CHECK(p.x[0].fs == 4657.9208);
  CHECK(p.x[1].fs == 8625.3352);
  CHECK(p.x[0].sm == 0.12);
  CHECK(p.x[1].sm == 0.15);
  CHECK(p.x[0].ss == 0.9);
  CHECK(p.x[1].ss == 0.95);
  CHECK(p.y[0].df0 == 50931.693);
  CHECK(p.y[1].df0 == 94293.84);
  CHECK(p.y[0].fm == 6615.0404);
  CHECK(p.y[1].fm == 12509.947);
  CHECK(p.y[0].fs == 6091.5092);
  CHECK(p.y[1].fs == 11443.875);
  CHECK(p.y[0].sm == 0.38786);
  CHECK(p.y[1].sm == 0.38786);
  CHECK(p.y[0].ss == 0.82534);
  CHECK(p.y[1].ss == 0.91309);

  // Our form of the same tire reads back to the same values.
  TmeasyParams back = read_tmeasy(tmeasy_json(p), "ours.json");
  for (const auto& f : fields()) {
    INFO(f.own);
    CHECK(*f.at(back) == *f.at(p));
  }
  // And the three keys without a meaning here change nothing, whatever their values.
  Json j = lfdm_hmmwv_json();
  j["step"] = 0.01;
  j["fzRdynco"] = 11417.1;
  j["rdyncoCrit"] = 0.5;
  j.erase("step");
  back = read_tmeasy(j, "t.json");
  for (const auto& f : fields()) CHECK(*f.at(back) == *f.at(p));

  // LFDM's sedan tire (data/json/sedan_TMeasy.json) differs in these keys.
  j = lfdm_hmmwv_json();
  j["jw"] = 4;
  j["r0"] = 0.3266;
  j["dfx0Pn"] = 142057.4736;
  j["dfx0P2n"] = 221755.19702;
  j["dfy0Pn"] = 56024.8623;
  j["dfy0P2n"] = 103723.224;
  CHECK(read_tmeasy(j, "sedan_TMeasy.json").x[1].df0 == 221755.19702);
}

TEST_CASE("TMeasy: Rill's load interpolation passes through the curves at Fzn and 2 Fzn", "[tmeasy]") {
  const TmeasyParams p = hmmwv();
  for (int dir = 0; dir < 2; ++dir) {
    const TmeasyCurve* c = dir == 0 ? &p.x[0] : &p.y[0];
    for (int i = 0; i < 2; ++i) {
      INFO("direction " << dir << ", load " << i + 1 << " Fzn");
      const TmeasyCurve at = tmeasy_curve_at_load(c, i + 1.0);
      // Forces q (2 p1 - p2/2 - (p1 - p2/2) q): exact up to the last bit or two of the subtraction.
      CHECK(at.df0 == Approx(c[i].df0).epsilon(2 * DBL_EPSILON).margin(0));
      CHECK(at.fm == Approx(c[i].fm).epsilon(2 * DBL_EPSILON).margin(0));
      CHECK(at.fs == Approx(c[i].fs).epsilon(2 * DBL_EPSILON).margin(0));
      CHECK(at.sm == Approx(c[i].sm).epsilon(2 * DBL_EPSILON).margin(0));
      CHECK(at.ss == Approx(c[i].ss).epsilon(2 * DBL_EPSILON).margin(0));
      // The same through the load state.
      const TmeasyLoadState st = tmeasy_at_load(p, (i + 1) * p.nominal_load);
      const TmeasyCurve& s = dir == 0 ? st.x : st.y;
      CHECK(s.fm == Approx(c[i].fm).epsilon(4 * DBL_EPSILON).margin(0));
      CHECK(s.sm == Approx(c[i].sm).epsilon(4 * DBL_EPSILON).margin(0));
    }
    CHECK(tmeasy_force_at_load(0.0, c[0].fm, c[1].fm) == 0.0);  // no load, no force
  }
  // Loads beyond max_load use the curve at max_load.
  CHECK(tmeasy_at_load(p, 3 * p.max_load).x.fm == tmeasy_at_load(p, p.max_load).x.fm);
  // The dynamic radius at Fzn: lambda r0 + (1 - lambda) (r0 - Fzn / kt).
  const double r_static = p.unloaded_radius - p.nominal_load / p.vertical_stiffness;
  CHECK(tmeasy_at_load(p, p.nominal_load).rdyn == Approx(0.375 * p.unloaded_radius + 0.625 * r_static));
}

TEST_CASE("TMeasy: the steady curve at Fzn has slope df0 at 0, fm at sm and fs from ss on", "[tmeasy]") {
  const TmeasyParams p = hmmwv();
  const double fz = p.nominal_load;
  for (int dir = 0; dir < 2; ++dir) {
    INFO((dir == 0 ? "pure longitudinal slip" : "pure lateral slip"));
    const TmeasyCurve& c = (dir == 0 ? &p.x[0] : &p.y[0])[0];
    auto force = [&](double s) {
      const Force f = dir == 0 ? steady(p, fz, s, 0) : steady(p, fz, 0, s);
      CHECK((dir == 0 ? f.fy : f.fx) == 0.0);
      return dir == 0 ? f.fx : f.fy;
    };
    CHECK(force(1e-9) / 1e-9 == Approx(c.df0).epsilon(1e-6));
    CHECK(force(0.0) == 0.0);
    CHECK(force(c.sm) == Approx(c.fm).epsilon(1e-12));
    CHECK(force(c.ss) == Approx(c.fs).epsilon(1e-12));
    CHECK(force(1.5 * c.ss) == Approx(c.fs).epsilon(1e-12));
    CHECK(force(20.0) == Approx(c.fs).epsilon(1e-12));
    CHECK(force(-c.sm) == Approx(-c.fm).epsilon(1e-12));  // odd in the slip
    // Rising to fm at sm, falling from there to fs at ss.
    double last = 0;
    for (int i = 1; i <= 200; ++i) {
      const double f = force(c.sm * i / 200.0);
      CHECK(f > last);
      last = f;
    }
    for (int i = 1; i <= 200; ++i) {
      const double f = force(c.sm + (c.ss - c.sm) * i / 200.0);
      CHECK(f < last);
      last = f;
    }
  }
}

TEST_CASE("TMeasy: combined slip never exceeds the larger maximum force and is odd in each slip", "[tmeasy]") {
  const TmeasyParams p = hmmwv();
  for (const double fz : {0.3 * p.nominal_load, p.nominal_load, 2 * p.nominal_load, p.max_load}) {
    const TmeasyLoadState st = tmeasy_at_load(p, fz);
    const double largest = std::max(st.x.fm, st.y.fm);
    double peak = 0;
    int over = 0, asymmetric = 0, against = 0;
    for (int i = -60; i <= 60; ++i)
      for (int k = -60; k <= 60; ++k) {
        const double sx = i / 40.0, sy = k / 40.0;  // up to 1.5 both ways
        const Force f = steady(p, fz, sx, sy);
        const double magnitude = std::hypot(f.fx, f.fy);
        peak = std::max(peak, magnitude);
        if (!(magnitude <= largest * (1 + 1e-12))) ++over;
        const Force mx = steady(p, fz, -sx, sy), my = steady(p, fz, sx, -sy);
        if (mx.fx != -f.fx || mx.fy != f.fy || my.fx != f.fx || my.fy != -f.fy) ++asymmetric;
        if (f.fx * sx < 0 || f.fy * sy < 0) ++against;  // the force acts with the slip
      }
    INFO("Fz = " << fz << " N, largest fm " << largest << " N, peak " << peak << " N");
    CHECK(over == 0);
    CHECK(asymmetric == 0);
    CHECK(against == 0);
    CHECK(peak > 0.95 * largest);  // and the grid comes near it
  }
}

TEST_CASE("TMeasy: the relaxation form settles on the steady force at constant velocities", "[tmeasy]") {
  const TmeasyParams p = hmmwv();
  const double fz = p.nominal_load;
  const TmeasyLoadState st = tmeasy_at_load(p, fz);
  struct Case {
    const char* name;
    double vx, vy, spin;  // spin: omega rdyn / vx
  };
  for (const Case& c : {Case{"driving", 10, 0, 1.05}, Case{"braking hard", 10, 0, 0.7}, Case{"cornering", 10, 0.8, 1.0},
                        Case{"combined", 5, -0.6, 1.1}, Case{"slow", 0.5, 0.05, 1.2}}) {
    INFO(c.name);
    const double omega = c.spin * c.vx / st.rdyn;
    const TmeasySlips s = tmeasy_slips(c.vx, c.vy, omega, st.rdyn);
    const TmeasyStiffness k = tmeasy_steady_stiffness(st, s.sx, s.sy, fz);
    const double fx = k.kx * s.sx, fy = k.ky * s.sy;
    // The deflection's time constant (d den + k) / (c den); run 30 of them.
    const double tau =
        std::max((p.longitudinal_damping * s.denominator + k.kx) / (p.longitudinal_stiffness * s.denominator),
                 (p.lateral_damping * s.denominator + k.ky) / (p.lateral_stiffness * s.denominator));
    const double h = std::min(1e-4, tau / 50);
    double xe = 0, ye = 0, gap_x = std::abs(fx), gap_y = std::abs(fy);
    TmeasyRelaxed r;
    bool monotone = true;
    for (double t = 0; t < 30 * tau; t += h) {
      r = tmeasy_relaxed(p, k, s, c.vx, c.vy, omega, st.rdyn, xe, ye);
      const double gx = std::abs(r.fx - fx), gy = std::abs(r.fy - fy);
      monotone = monotone && gx <= gap_x * (1 + 1e-12) + 1e-9 && gy <= gap_y * (1 + 1e-12) + 1e-9;
      gap_x = gx;
      gap_y = gy;
      xe += h * r.dxe;
      ye += h * r.dye;
    }
    INFO("sx " << s.sx << ", sy " << s.sy << ", tau " << tau << " s, steady " << fx << ", " << fy << " N");
    CHECK(std::abs(fx) + std::abs(fy) > 100);  // a case with force
    CHECK(r.fx == Approx(fx).epsilon(1e-6).margin(1e-6));
    CHECK(r.fy == Approx(fy).epsilon(1e-6).margin(1e-6));
    CHECK(std::abs(r.dxe) < 1e-9);
    CHECK(monotone);  // first order: no overshoot
  }
}

TEST_CASE("TMeasy: at standstill a tread deflection decays without oscillating", "[tmeasy]") {
  const TmeasyParams p = hmmwv();
  for (const double fz : {p.nominal_load, 0.0}) {
    for (const double h : {1e-3, 1e-2}) {
      INFO("Fz " << fz << " N, step " << h << " s");
      if (fz == 0.0 && h == 1e-2) continue;  // no load: rate cx / dx = 50/s, beyond explicit Euler at 0.01 s
      const TmeasyLoadState st = tmeasy_at_load(p, fz);
      const TmeasySlips s = tmeasy_slips(0, 0, 0, st.rdyn);
      CHECK(s.sx == 0.0);
      CHECK(s.denominator == kTmeasySlipVelocity);
      const TmeasyStiffness k = tmeasy_steady_stiffness(st, s.sx, s.sy, fz);
      double xe = 0.01, ye = -0.005;
      bool finite = true, decreasing = true, same_sign = true, damped = true;
      for (int i = 0; i < 2000; ++i) {
        const TmeasyRelaxed r = tmeasy_relaxed(p, k, s, 0, 0, 0, st.rdyn, xe, ye);
        finite = finite && std::isfinite(r.fx) && std::isfinite(r.fy) && std::isfinite(r.dxe) && std::isfinite(r.dye);
        // The force pulls back toward zero deflection, never beyond the spring's.
        // (Without load the spring and the damper cancel: the force is zero up to rounding.)
        const double spring_x = p.longitudinal_stiffness * xe, spring_y = p.lateral_stiffness * ye;
        damped = damped && r.fx / spring_x >= -1e-12 && r.fx / spring_x <= 1 && r.fy / spring_y >= -1e-12 &&
                 r.fy / spring_y <= 1;
        const double nx = xe + h * r.dxe, ny = ye + h * r.dye;
        decreasing = decreasing && std::abs(nx) < std::abs(xe) && std::abs(ny) < std::abs(ye);
        same_sign = same_sign && nx != 0 && ny != 0 && (nx > 0) == (xe > 0) && (ny > 0) == (ye > 0);
        xe = nx;
        ye = ny;
      }
      CHECK(finite);
      CHECK(decreasing);
      CHECK(same_sign);
      CHECK(damped);
      CHECK(std::abs(xe) < 0.01);
    }
  }
}

TEST_CASE("TMeasy guess: Chrono's HMMWV tire from its size and load", "[tmeasy]") {
  // Chrono's HMMWV_TMeasyTire: 37 x 12.5 R16.5, 3850 lbf (Goodyear's military brochure), truck.
  const TireSize size = parse_tire_size("37x12.5R16.5", "test");
  CHECK(size.width == Approx(12.5 * kInch));
  CHECK(size.rim_diameter == Approx(16.5 * kInch));
  CHECK(size.aspect_ratio == Approx(0.82));  // (37 - 16.5) / 2 / 12.5
  const double load = 3850 * 4.4482216153;
  TmeasyParams g = tmeasy_guess(load, size.width, size.aspect_ratio, size.rim_diameter, true, 37.6, 6.5);
  // The published values (LFDM's file, Chrono's HMMWV_TMeasyTire.json) to their printed digits.
  const TmeasyParams pub = hmmwv();
  CHECK(g.unloaded_radius == Approx(pub.unloaded_radius).epsilon(1e-12));
  CHECK(g.nominal_load == Approx(pub.nominal_load).epsilon(1e-8));
  CHECK(g.max_load == Approx(pub.max_load).epsilon(1e-8));
  CHECK(g.vertical_stiffness == Approx(pub.vertical_stiffness).epsilon(1e-6));
  CHECK(g.rolling_resistance == pub.rolling_resistance);
  CHECK(g.rdyn_coefficient[0] == pub.rdyn_coefficient[0]);
  CHECK(g.rdyn_coefficient[1] == pub.rdyn_coefficient[1]);
  for (int i = 0; i < 2; ++i)
    for (int dir = 0; dir < 2; ++dir) {
      const TmeasyCurve& a = (dir == 0 ? &g.x[0] : &g.y[0])[i];
      const TmeasyCurve& b = (dir == 0 ? &pub.x[0] : &pub.y[0])[i];
      INFO("direction " << dir << ", load " << i + 1 << " Fzn");
      CHECK(a.df0 == Approx(b.df0).epsilon(1e-6));
      CHECK(a.fm == Approx(b.fm).epsilon(1e-7));
      CHECK(a.fs == Approx(b.fs).epsilon(1e-7));
      CHECK(a.sm == b.sm);
      CHECK(a.ss == b.ss);
    }
  // The published tread stiffnesses are 0.9 and 0.8 times Fzn / deflection, half of Chrono's
  // guess (0.9 and 0.8 times max load / deflection, the vertical stiffness); their damping was set by
  // hand. Chrono's guess damps with 0.5 sqrt(c m_tire).
  CHECK(pub.longitudinal_stiffness == Approx(0.5 * g.longitudinal_stiffness).epsilon(1e-6));
  CHECK(pub.lateral_stiffness == Approx(0.5 * g.lateral_stiffness).epsilon(1e-6));
  CHECK(g.longitudinal_damping == Approx(0.5 * std::sqrt(g.longitudinal_stiffness * 37.6)));

  // The same through a file's "guess".
  const Json j = {
      {"type", "TMeasy"},
      {"wheel_inertia", 6.5},
      {"guess", {{"tire_size", "37x12.5R16.5"}, {"max_load", load}, {"vehicle_type", "truck"}, {"tire_mass", 37.6}}}};
  TmeasyParams f = read_tmeasy(j, "hmmwv_guess.json");
  for (const auto& field : fields()) {
    INFO(field.own);
    CHECK(*field.at(f) == *field.at(g));
  }
}

TEST_CASE("TMeasy guess: a passenger tire is consistent", "[tmeasy]") {
  const Json j = {{"type", "TMeasy"},
                  {"wheel_inertia", 1.1},
                  {"guess",
                   {{"tire_size", "255/50R19"},
                    {"load_index", 107},
                    {"vehicle_type", "passenger"},
                    {"tire_mass", 12},
                    {"inflation_pressure", 2.2e5},
                    {"rated_pressure", 2.5e5}}}};
  const TmeasyParams p = read_tmeasy(j, "car.json");
  CHECK(p.unloaded_radius == Approx(0.255 * 0.5 + 0.5 * 19 * kInch));
  CHECK(p.nominal_load == Approx(0.5 * 975 * 9.81 * std::pow(2.2 / 2.5, 0.8)));
  CHECK(p.vertical_stiffness == Approx(975 * 9.81 / (0.16 * 0.255 * 0.5)));
  CHECK(p.wheel_inertia == 1.1);
  for (const TmeasyCurve* c : {p.x, p.y}) {
    CHECK(c[1].df0 > c[0].df0);  // stiffer under more load
    CHECK(c[1].fm > c[0].fm);
    for (int i = 0; i < 2; ++i) {
      const double mu = c[i].fm / ((i + 1) * p.nominal_load);  // fm = mu Fz
      CHECK(mu > 0.85);
      CHECK(mu < 1.15);
      CHECK(c[i].fs < c[i].fm);
    }
  }
  // The combined force at Fzn stays below mu Fz with mu the larger of the two.
  double peak = 0;
  for (int i = -40; i <= 40; ++i)
    for (int k = -40; k <= 40; ++k) {
      const Force f = steady(p, p.nominal_load, i / 40.0, k / 40.0);
      peak = std::max(peak, std::hypot(f.fx, f.fy));
    }
  CHECK(peak <= std::max(p.x[0].fm, p.y[0].fm) * (1 + 1e-12));
  // Without the pressures the load is the rated one.
  Json rated = j;
  rated["guess"].erase("inflation_pressure");
  rated["guess"].erase("rated_pressure");
  CHECK(read_tmeasy(rated, "car.json").nominal_load == Approx(0.5 * 975 * 9.81));
}

TEST_CASE("TMeasy guess: load indices", "[tmeasy]") {
  CHECK(tire_max_load(121) == Approx(1450 * 9.81));
  CHECK(tire_max_load(108) == Approx(1000 * 9.81));
  CHECK(tire_max_load(0) == Approx(45 * 9.81));
  CHECK(tire_max_load(279) == Approx(136000 * 9.81));
  for (int li = 0; li < 279; ++li) {
    INFO("LI " << li);
    CHECK(tire_max_load(li + 1) > tire_max_load(li));
    // The series repeats tenfold every 80 indices, rounded (LI 77 = 412 kg, LI 157 = 4125 kg).
    if (li < 200) CHECK(tire_max_load(li + 80) == Approx(10 * tire_max_load(li)).epsilon(0.005));
  }
  // Chrono's guess gives a valid tire (tmeasy_guess validates) across loads and sizes.
  for (const char* size : {"125/80R12", "255/50R19", "315/80R22.5", "37x12.5R16.5", "46x18R21LT"})
    for (const int li : {0, 60, 100, 150, 200, 279})
      for (const bool truck : {true, false}) {
        INFO(size << ", LI " << li << (truck ? ", truck" : ", passenger"));
        const TireSize s = parse_tire_size(size, "test");
        CHECK_NOTHROW(tmeasy_guess(tire_max_load(li), s.width, s.aspect_ratio, s.rim_diameter, truck, 20, 2,
                                   li < 100 ? 0.8 : 1.2));
      }
  CHECK_THROWS_WITH(tire_max_load(280), Contains("key 'load_index': value 280"));
  CHECK_THROWS_WITH(tire_max_load(-1), Contains("key 'load_index': value -1"));
}

TEST_CASE("TMeasy guess: tire sizes", "[tmeasy]") {
  struct Good {
    const char* text;
    double width, ratio, rim;
  };
  for (const Good& g : {Good{"255/50R19", 0.255, 0.5, 19 * kInch}, Good{"P215/65R15", 0.215, 0.65, 15 * kInch},
                        Good{"LT265/75R16", 0.265, 0.75, 16 * kInch}, Good{"315/80R22.5", 0.315, 0.8, 22.5 * kInch},
                        Good{"215/65R16C", 0.215, 0.65, 16 * kInch}, Good{"245/40ZR18", 0.245, 0.4, 18 * kInch},
                        Good{"33X12.50R15LT", 12.5 * kInch, 9 / 12.5, 15 * kInch},
                        Good{"35x12.5-15", 12.5 * kInch, 10 / 12.5, 15 * kInch}}) {
    INFO(g.text);
    const TireSize s = parse_tire_size(g.text, "f.json");
    CHECK(s.width == Approx(g.width));
    CHECK(s.aspect_ratio == Approx(g.ratio));
    CHECK(s.rim_diameter == Approx(g.rim));
  }
  for (const char* bad : {"", "255/50", "255-50R19", "37x12.5", "255/50R19 107W", "255/50 R19", "abc", "12.5x37R16.5",
                          "25/50R19", "255/50R1"}) {
    INFO("'" << bad << "'");
    CHECK_THROWS_AS(parse_tire_size(bad, "f.json"), InputError);
    Json j = {{"type", "TMeasy"},
              {"wheel_inertia", 1},
              {"guess", {{"tire_size", bad}, {"load_index", 100}, {"vehicle_type", "truck"}, {"tire_mass", 10}}}};
    const std::string e = error_of(j);
    CHECK_THAT(e, Contains("t.json: key 'guess.tire_size': value '" + std::string(bad) + "'"));
  }
  CHECK_THROWS_WITH(parse_tire_size("12.5x37R16.5", "f.json"), Contains("overall diameter (12.5 in) not above"));
}

TEST_CASE("TMeasy: each value out of its range is refused by the readers and by validate()", "[tmeasy]") {
  const TmeasyParams good = hmmwv();
  CHECK(validate_error(good).empty());
  for (const auto& f : fields()) {
    INFO(f.own);
    for (const double bad : {-1.0, 1e12}) {
      Json lfdm = lfdm_hmmwv_json();
      lfdm[f.lfdm] = bad;
      Json own = tmeasy_json(good);
      own_slot(own, f.own) = bad;
      const std::string shown = bad < 0 ? "-1" : "1000000000000";
      CHECK_THAT(error_of(lfdm), Contains(std::string("t.json: key '") + f.lfdm + "': value " + shown));
      CHECK_THAT(error_of(own), Contains(std::string("t.json: key '") + f.own + "': value " + shown));
      TmeasyParams p = good;
      *f.at(p) = bad;
      CHECK_THAT(validate_error(p), Contains(std::string("built: key '") + f.own + "': value " + shown));
    }
    TmeasyParams p = good;
    *f.at(p) = std::nan("");  // only code can make a NaN (JSON has none)
    CHECK_THAT(validate_error(p), Contains(std::string("built: key '") + f.own + "': value nan"));
  }
}

TEST_CASE("TMeasy: refusals name the key and the value", "[tmeasy]") {
  const TmeasyParams good = hmmwv();
  const Json own = tmeasy_json(good), lfdm = lfdm_hmmwv_json();

  SECTION("a misspelled key") {
    Json j = own;
    j["nominal_lod"] = 8000;
    CHECK_THAT(error_of(j), Contains("t.json: key 'nominal_lod': value 8000: unknown key"));
    j = own;
    j["longitudinal"]["smm"] = {0.1, 0.2};
    CHECK_THAT(error_of(j), Contains("t.json: key 'longitudinal.smm': value [0.1,0.2]: unknown key"));
    j = lfdm;
    j["sxmPN"] = 0.1;
    CHECK_THAT(error_of(j), Contains("t.json: key 'sxmPN': value 0.1: unknown key"));
    j = own;
    j.erase("lateral_damping");
    CHECK_THAT(error_of(j), Contains("key 'lateral_damping': is required but missing"));
    j = lfdm;
    j.erase("dy");
    CHECK_THAT(error_of(j), Contains("key 'dy': is required but missing"));
  }
  SECTION("a wrong type") {
    Json j = own;
    j["type"] = "Pac02";
    CHECK_THAT(error_of(j), Contains("key 'type': value \"Pac02\" is not one of: TMeasy"));
    j = own;
    j["rdyn_coefficient"] = {0.375};
    CHECK_THAT(error_of(j), Contains("key 'rdyn_coefficient': value [0.375] is not an array of two numbers"));
    CHECK_THAT(error_of(Json{{"foo", 1}}), Contains("t.json: not a TMeasy tire"));
  }
  SECTION("sm >= ss") {
    Json j = own;
    j["longitudinal"]["sm"][0] = 0.95;
    CHECK_THAT(error_of(j),
               Contains("t.json: key 'longitudinal.sm[0]': value 0.95 must be below longitudinal.ss[0] = 0.9"));
    j = lfdm;
    j["sysP2n"] = 0.3;
    CHECK_THAT(error_of(j), Contains("t.json: key 'symP2n': value 0.38786 must be below sysP2n = 0.3"));
    TmeasyParams p = good;
    p.y[0].ss = p.y[0].sm;
    CHECK_THAT(validate_error(p), Contains("built: key 'lateral.sm[0]': value 0.38786 must be below"));
  }
  SECTION("fs > fm") {
    Json j = lfdm;
    j["fysPn"] = 7000;
    CHECK_THAT(error_of(j), Contains("key 'fysPn': value 7000 must not exceed fymPn = 6615.0404"));
  }
  SECTION("df0 below 2 fm / sm: LFDM's Audi tire (18dof-gpu/data/json/audi/tmeasy.json)") {
    const Json audi = {{"jw", 4},
                       {"rr", 0.01},
                       {"r0", 0.336423},
                       {"dfx0Pn", 151447.29},
                       {"fxmPn", 16362.7806},
                       {"fxmP2n", 27665.8762},
                       {"fxsPn", 14487.9968},
                       {"fxsP2n", 22356.8689},
                       {"sxmPn", 0.08},
                       {"sxmP2n", 0.10},
                       {"fymPn", 12402.5},
                       {"fymP2n", 20328.6638},
                       {"fysPn", 11421.5798},
                       {"fysP2n", 18596.2968}};
    Json j = lfdm;
    for (const auto& [k, v] : audi.items()) j[k] = v;
    const std::string e = error_of(j);
    CHECK_THAT(e, Contains("t.json: key 'dfx0Pn': value 151447.29 is below 2 fm / sm = 409069.515"));
    CHECK_THAT(e, Contains("expected df0 >= 409069.515"));
  }
  SECTION("curves that turn bad between the given loads and max_load") {
    Json j = lfdm;
    j["sxmP2n"] = 0.25;  // sm = 2 * 0.12 - 0.25 < 0 at zero load
    CHECK_THAT(error_of(j), Contains("key 'sxmP2n': value 0.25 with sxmPn = 0.12 makes the slip"));
    CHECK_THAT(error_of(j), Contains("near zero load"));
    j = lfdm;
    j["pnmax"] = 68000;  // the df0 quadratic crosses zero at 5.6 Fzn
    CHECK_THAT(error_of(j), Contains("key 'dfx0P2n': value 236412.79 with dfx0Pn = 151447.2"));
    CHECK_THAT(error_of(j), Contains("at max_load ('pnmax') = 68000 N"));
    j = lfdm;
    j["pnmax"] = 8000;
    CHECK_THAT(error_of(j), Contains("key 'pnmax': value 8000 must exceed pn = 8562.8266"));
    j = lfdm;
    j["kt"] = 50000;
    CHECK_THAT(error_of(j), Contains("key 'pnmax': value 29969.893 presses the tire by"));
    CHECK_THAT(error_of(j), Contains("kt = 50000 N/m"));
  }
  SECTION("LFDM's keys mixed with ours") {
    Json j = lfdm;
    j["nominal_load"] = 8000;
    std::string e = error_of(j);
    CHECK_THAT(e, Contains("key 'nominal_load' (value 8000) is ours"));
    CHECK_THAT(e, Contains("is LFDM's"));
    CHECK_THAT(e, Contains("a tire file takes one form"));
    j = own;
    j["pn"] = 8562.8266;
    CHECK_THAT(error_of(j), Contains("key 'pn' (value 8562.8266) is LFDM's"));
    j = lfdm;
    j["type"] = "TMeasy";
    CHECK_THAT(error_of(j), Contains("key 'type' (value \"TMeasy\") is ours"));
  }
  SECTION("the guess") {
    const Json g = {
        {"type", "TMeasy"},
        {"wheel_inertia", 6.5},
        {"guess",
         {{"tire_size", "37x12.5R16.5"}, {"load_index", 121}, {"vehicle_type", "truck"}, {"tire_mass", 37.6}}}};
    CHECK(error_of(g).empty());
    Json j = g;
    j["nominal_load"] = 9000;
    CHECK_THAT(error_of(j), Contains("key 'nominal_load': value 9000 is not valid beside 'guess'"));
    j = g;
    j.erase("wheel_inertia");
    CHECK_THAT(error_of(j), Contains("key 'wheel_inertia': is required beside 'guess'"));
    j = g;
    j["guess"]["max_load"] = 14000;
    CHECK_THAT(error_of(j), Contains("key 'guess.load_index': and 'guess.max_load' are both given"));
    j = g;
    j["guess"]["load_index"] = 300;
    CHECK_THAT(error_of(j), Contains("key 'guess.load_index': value 300 is outside the allowed range [0, 279]"));
    j = g;
    j["guess"]["vehicle_type"] = "bus";
    CHECK_THAT(error_of(j), Contains("key 'guess.vehicle_type': value \"bus\" is not one of: truck, passenger"));
    j = g;
    j["guess"]["inflation_pressure"] = 3e5;
    CHECK_THAT(error_of(j), Contains("key 'guess.rated_pressure': is required beside the other pressure"));
    j = g;
    j["guess"]["tire_mas"] = 37.6;
    CHECK_THAT(error_of(j), Contains("key 'guess.tire_mas': value 37.6: unknown key"));
    j = g;
    j["guess"]["tire_mass"] = -2;
    CHECK_THAT(error_of(j), Contains("key 'guess.tire_mass': value -2 is outside the allowed range (0, 10000] kg"));
  }
}
