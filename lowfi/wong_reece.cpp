#include "lowfi/wong_reece.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>
#include <cstdio>
#include <cstdlib>
#include <mutex>

#include <fmt/format.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gsl/gsl_roots.h>

#include "core/errors.hpp"

namespace terracal::lowfi {

namespace {

// GSL's default error handler aborts the process (e.g. on a round-off warning from QAGS). Within a
// call we want status codes instead, which we turn into RunError. The handler is process-global and
// calls run on many threads at once (a calibration's chains), so one handler is installed for good:
// it returns the status code on a thread inside such a call and behaves as GSL's default (report,
// abort) everywhere else.
thread_local int gsl_status_code_calls = 0;

void gsl_handler(const char* reason, const char* file, int line, int gsl_errno) {
  if (gsl_status_code_calls > 0) return;
  std::fprintf(stderr, "gsl: %s:%d: ERROR: %s (error %d)\n", file, line, reason, gsl_errno);
  std::abort();
}

class GslStatusCodes {
 public:
  GslStatusCodes() {
    static std::once_flag installed;
    std::call_once(installed, [] { gsl_set_error_handler(&gsl_handler); });
    ++gsl_status_code_calls;
  }
  ~GslStatusCodes() { --gsl_status_code_calls; }
  GslStatusCodes(const GslStatusCodes&) = delete;
  GslStatusCodes& operator=(const GslStatusCodes&) = delete;
};

// Stresses on the rim for one trial entry angle.
struct Contact {
  double r, b, slip;
  double k_bekker;  // (Kc/b + Kphi) r^n: sigma = k_bekker (cos θ_eq − cos θ1)^n
  double n, cohesion, tan_phi, janosi_k;
  ShearDisplacement displacement = ShearDisplacement::rim;
  double ke = 0, damping_v = 0;  // rear rebound stiffness [Pa/m]; damping x carriage speed [Pa]
  // With a patch width: k_bekker = (Kc / b + Kphi) rn, b from the patch (set_entry_angle).
  bool patch_width = false;
  double kc = 0, kphi = 0, rn = 0;
  // Per-angle slip sinkage (WongReeceOptions::local_slip_sinkage): nullptr when off.
  const SlipSinkage* local_stretch = nullptr;
  double theta1 = 0, theta_m = 0, theta_r = 0;  // theta_r: where the rear lets go (0: no rear)
  double patch_b = 0;                           // with a patch width: its Bekker width at theta1
  // Worked out once per entry angle (set_entry_angle) or per wheel, not at every quadrature point:
  // the integrands are nearly all of the calibrator's time.
  double cos_theta1 = 1, sin_theta1 = 0, sin_2theta1 = 0;
  double bekker_bottom = 0;  // bekker(0): the stress at the bottom, where the elastic rear starts
  double stretch_slip = 1;   // with local_stretch: the stretch at the wheel's slip (the law's rn)

  // Bekker stress at the equivalent front angle te, from cos(te); the difference of cosines can
  // round slightly below zero at te = θ1, and pow of a negative base is NaN.
  double bekker_at_cos(double cos_te) const { return k_bekker * std::pow(std::max(0.0, cos_te - cos_theta1), n); }
  double bekker(double te) const { return bekker_at_cos(std::cos(te)); }
  // σ at θ, given sin θ and cos θ.
  double sigma(double theta, double sin_t, double cos_t) const {
    if (theta < 0) return std::max(0.0, bekker_bottom - ke * r * (1.0 - cos_t));  // rear rebound
    if (theta >= theta_m) {
      double front = bekker_at_cos(cos_t);
      if (local_stretch && theta > 0)  // k (z / f(theta))^n over k (z / f(0))^n: rn holds f(0)
        front *= std::pow(stretch_slip / pressure_sinkage_stretch(*local_stretch, 1 - (1 - slip) * cos_t, n), n);
      return front + damping_v * sin_t;
    }
    // Rear: [0, θm] is mapped linearly onto [θ1, θm] of the front law, so that σ(0) = 0 and σ is
    // continuous at θm. Only reached when θm > 0 (the rear piece is empty otherwise).
    return bekker(theta1 - theta / theta_m * (theta1 - theta_m));
  }
  // The shear displacement (WongReeceOptions::shear_displacement) at θ, given sin θ; slip < 1 is
  // validated.
  double displacement_at(double theta, double sin_t) const {
    const double chord = sin_theta1 - sin_t;
    if (displacement == ShearDisplacement::rim) return r * ((theta1 - theta) - (1.0 - slip) * chord);
    const double cos2_integral = 0.5 * (theta1 - theta) + 0.25 * (sin_2theta1 - std::sin(2 * theta));
    return r / (1.0 - slip) * (chord - (1.0 - slip) * cos2_integral);
  }
  // τ at θ, given sin θ and σ(θ).
  double tau(double theta, double sin_t, double sigma_t) const {
    const double j = displacement_at(theta, sin_t);
    // Janosi-Hanamoto with the sign of j: in skid (s < 0) the soil shears the rim backward.
    const double developed = -std::expm1(-std::abs(j) / janosi_k);
    return std::copysign((cohesion + sigma_t * tan_phi) * developed, j);
  }
  // An upper bound of |σ| + |τ|, the scale for absolute quadrature tolerances (DBP can be ~0).
  double stress_scale() const {
    const double sigma_max = bekker_bottom + damping_v;
    return sigma_max + cohesion + sigma_max * tan_phi;
  }
};

enum class Quantity { Vertical, Drawbar, Torque };

// One piece of the contact, integrated over v in [0, 1] with theta = end + toward v^2: the piece's
// stress (cos θ − cos θ1)^n behaves like a power n < 1 of the distance from `end` (the entry angle,
// or the rear's zero), and the Janosi shear develops over a short arc there; in v that becomes a
// power 2n + 1 and an arc √ times wider, which QAGS resolves with about a third of the points.
struct Integrand {
  const Contact* contact;
  Quantity q;
  double end, toward;  // θ(v) = end + toward v², dθ = 2 |toward| v dv
};

double integrand(double v, void* p) {
  const auto* in = static_cast<const Integrand*>(p);
  const Contact& c = *in->contact;
  const double theta = in->end + in->toward * v * v, jacobian = 2 * std::abs(in->toward) * v;
  const double sin_t = std::sin(theta), cos_t = std::cos(theta);
  const double s = c.sigma(theta, sin_t, cos_t), t = c.tau(theta, sin_t, s);
  switch (in->q) {
    case Quantity::Vertical:
      return jacobian * (s * cos_t + t * sin_t);
    case Quantity::Drawbar:
      return jacobian * (t * cos_t - s * sin_t);
    case Quantity::Torque:
      return jacobian * t;
  }
  return 0.0;
}

struct WorkspaceFree {
  void operator()(gsl_integration_workspace* w) const { gsl_integration_workspace_free(w); }
};
using Workspace = std::unique_ptr<gsl_integration_workspace, WorkspaceFree>;
constexpr size_t kWorkspaceIntervals = 1000;

// ∫_-θr^θ1 of the quantity's integrand (without the r b or r² b factor), the elastic rear [-θr, 0],
// the rear [0, θm] and the front [θm, θ1] separately because σ has kinks at 0 and θm. Each piece is
// taken in v (Integrand) from the end where σ has its algebraic end-point behaviour (cos θ − cos θ1)^n:
// θ1 for the front, 0 for the rear (it maps onto the front law from θ1), and the bottom for the elastic
// rear (smooth, where the rebound starts). QAGS copes with what is left.
double integrate(const Contact& c, Quantity q, double rel_tol, gsl_integration_workspace* w) {
  const double eps_abs = 0.1 * rel_tol * c.stress_scale() * c.theta1;
  double total = 0.0;
  const double bounds[4] = {-c.theta_r, 0.0, c.theta_m, c.theta1};
  for (int piece = 0; piece < 3; ++piece) {
    const double a = bounds[piece], b = bounds[piece + 1];
    if (!(b > a)) continue;  // θm = 0 or θm = θ1: one piece is empty
    Integrand in = piece == 1 ? Integrand{&c, q, a, b - a} : Integrand{&c, q, b, a - b};
    gsl_function f{&integrand, &in};
    double result = 0, abserr = 0;
    const int status = gsl_integration_qags(&f, 0.0, 1.0, eps_abs, rel_tol, kWorkspaceIntervals, w, &result, &abserr);
    // A GSL warning with a still-small error estimate (round-off at a very tight rel_tol) is accepted.
    if (status != GSL_SUCCESS && !(abserr <= 1e-6 * std::max(std::abs(result), c.stress_scale() * (b - a))))
      throw RunError(
          fmt::format("wong_reece: quadrature over [{}, {}] rad at entry angle {} rad failed: {} "
                      "(estimate {}, error {})",
                      a, b, c.theta1, gsl_strerror(status), result, abserr));
    total += result;
  }
  return total;
}

void set_entry_angle(Contact& c, double theta1, const WongReeceOptions& o) {
  c.theta1 = theta1;
  c.cos_theta1 = std::cos(theta1);
  c.sin_theta1 = std::sin(theta1);
  c.sin_2theta1 = std::sin(2 * theta1);
  // c1 + c2 s can leave [0, 1] (e.g. c1 + c2 s < 0 in deep skid): then the whole contact is front or rear.
  c.theta_m = std::clamp((o.c1 + o.c2 * c.slip) * theta1, 0.0, theta1);
  // The elastic rear lets go where the rebound has taken back the bottom's pressure; with a patch
  // width, that pressure and the patch's length depend on each other: a few fixed-point rounds (the
  // rear is a small part of the patch).
  c.theta_r = 0;
  for (int round = 0; round < (c.patch_width ? 4 : 1); ++round) {
    if (c.patch_width) {
      const double length = c.r * (std::sin(theta1) + std::sin(c.theta_r));
      const double bw = length * c.b / (length + c.b);  // 2 A / P of a length x width rectangle
      // A negative Kc leaves a narrow patch without strength: it carries no pressure, and the
      // wheel sinks on to a wider patch (the entry angle's bracket starts from a sliver of a
      // millimetre). Refused only where the equilibrium itself lies there (wong_reece()).
      c.patch_b = bw;
      c.k_bekker = std::max(0.0, (c.kc / bw + c.kphi) * c.rn);
    }
    c.bekker_bottom = c.bekker(0.0);
    c.theta_r = c.ke > 0 ? std::acos(std::max(-1.0, 1.0 - c.bekker_bottom / (c.ke * c.r))) : 0.0;
  }
}

void require(bool ok, const char* name, double value, const char* range) {
  if (!ok) throw InputError(fmt::format("wong_reece: {} = {}: expected {}", name, value, range));
}

void validate(const ScmSoil& soil, const WongReeceWheel& wheel, double load, double slip, const WongReeceOptions& o) {
  // `x > 0` and friends are false for NaN, so these also reject non-finite values.
  require(std::isfinite(wheel.radius) && wheel.radius > 0, "wheel radius", wheel.radius, "a finite value > 0 m");
  require(std::isfinite(wheel.width) && wheel.width > 0, "wheel width", wheel.width, "a finite value > 0 m");
  require(std::isfinite(load) && load > 0, "load", load, "a finite value > 0 N");
  require(slip > -1 && slip < 1, "slip", slip, "-1 < slip < 1");
  require(std::isfinite(soil.n) && soil.n > 0, "soil n", soil.n, "a finite value > 0");
  require(std::isfinite(soil.Kc), "soil Kc", soil.Kc, "a finite value");
  require(std::isfinite(soil.Kphi), "soil Kphi", soil.Kphi, "a finite value");
  const double k_sum = soil.Kc / wheel.width + soil.Kphi;
  require(std::isfinite(k_sum) && k_sum > 0, "soil Kc/b + Kphi", k_sum, "> 0 Pa/m^n (b = wheel width)");
  require(std::isfinite(soil.cohesion) && soil.cohesion >= 0, "soil cohesion", soil.cohesion, "a finite value >= 0 Pa");
  require(soil.friction_deg >= 0 && soil.friction_deg < 90, "soil friction_deg", soil.friction_deg,
          "in [0, 90) degrees");
  require(std::isfinite(soil.janosi_k) && soil.janosi_k > 0, "soil janosi_k", soil.janosi_k, "a finite value > 0 m");
  require(std::isfinite(o.c1), "option c1", o.c1, "a finite value");
  require(std::isfinite(o.c2), "option c2", o.c2, "a finite value");
  require(o.rel_tol >= 1e-14 && o.rel_tol <= 1e-3, "option rel_tol", o.rel_tol, "in [1e-14, 1e-3]");
  require(o.rear_stiffness >= 0 && std::isfinite(o.rear_stiffness), "option rear_stiffness", o.rear_stiffness,
          "a finite value >= 0 Pa/m");
  require(o.damping >= 0 && std::isfinite(o.damping), "option damping", o.damping, "a finite value >= 0 Pa s/m");
  require(o.carriage_speed >= 0 && std::isfinite(o.carriage_speed), "option carriage_speed", o.carriage_speed,
          "a finite value >= 0 m/s");
}

// What Brent's callback needs: the equilibrium residual, and a place for an exception that must not
// unwind through GSL's C frames.
struct Equilibrium {
  Contact* contact;
  const WongReeceOptions* options;
  gsl_integration_workspace* w;
  double load;
  std::exception_ptr error;

  // Vertical force [N] minus the load at entry angle theta1.
  double residual(double theta1) {
    set_entry_angle(*contact, theta1, *options);
    return contact->r * contact->b * integrate(*contact, Quantity::Vertical, options->rel_tol, w) - load;
  }
  static double call(double theta1, void* p) {
    auto* e = static_cast<Equilibrium*>(p);
    try {
      return e->residual(theta1);
    } catch (...) {
      e->error = std::current_exception();
      return std::nan("");  // makes Brent stop with GSL_EBADFUNC
    }
  }
};

struct SolverFree {
  void operator()(gsl_root_fsolver* s) const { gsl_root_fsolver_free(s); }
};

// Brackets the smallest entry angle that carries the load (the wheel sinks until it first balances),
// then refines it with Brent.
double solve_entry_angle(Equilibrium& eq, double rel_tol) {
  const double top = M_PI / 2;  // deeper than the axle: not a rigid-wheel contact any more
  constexpr int kGrid = 24;
  // Below 1e-3 rad the sinkage is ~r·5e-7 m: step down further only for a very light load.
  constexpr double kStart = 1e-3;
  double lo = kStart, hi = 0;
  bool bracketed = false;
  while (eq.residual(lo) >= 0) {
    bracketed = true;
    hi = lo;
    lo *= 0.1;
    if (lo < 1e-9)
      throw RunError(
          fmt::format("wong_reece: load {} N is carried already at an entry angle below 1e-9 rad; "
                      "too light to resolve",
                      eq.load));
  }
  // A coarse upward scan, so that Brent gets the first sign change rather than any.
  for (int i = 1; i <= kGrid && !bracketed; ++i) {
    const double theta = kStart + (top - kStart) * i / kGrid;
    if (eq.residual(theta) >= 0) {
      bracketed = true;
      hi = theta;
    } else {
      lo = theta;
    }
  }
  if (!bracketed) {
    set_entry_angle(*eq.contact, top, *eq.options);
    throw RunError(
        fmt::format("wong_reece: no entry angle in (0, pi/2] carries the load of {} N (at pi/2 the soil "
                    "carries only {} N): the wheel would sink past its axle",
                    eq.load, eq.residual(top) + eq.load));
  }

  std::unique_ptr<gsl_root_fsolver, SolverFree> solver(gsl_root_fsolver_alloc(gsl_root_fsolver_brent));
  gsl_function f{&Equilibrium::call, &eq};
  gsl_root_fsolver_set(solver.get(), &f, lo, hi);
  for (int iter = 0; iter < 200; ++iter) {
    const int status = gsl_root_fsolver_iterate(solver.get());
    if (eq.error) std::rethrow_exception(eq.error);
    if (status != GSL_SUCCESS)
      throw RunError(fmt::format("wong_reece: Brent on the entry angle failed: {}", gsl_strerror(status)));
    const double a = gsl_root_fsolver_x_lower(solver.get()), b = gsl_root_fsolver_x_upper(solver.get());
    if (gsl_root_test_interval(a, b, 0.0, rel_tol) == GSL_SUCCESS) return gsl_root_fsolver_root(solver.get());
  }
  throw RunError("wong_reece: Brent on the entry angle did not converge in 200 iterations");
}

}  // namespace

WongReeceResult wong_reece(const ScmSoil& soil, const WongReeceWheel& wheel, double load, double slip,
                           const WongReeceOptions& options) {
  validate(soil, wheel, load, slip, options);
  const GslStatusCodes gsl_guard;
  Workspace w(gsl_integration_workspace_alloc(kWorkspaceIntervals));

  const double r = wheel.radius, b = wheel.width;
  // Slip sinkage: sigma = k (z / f)^n, f the stretch that gives Lyasko's ratio at this slip.
  const double stretch = options.slip_sinkage ? pressure_sinkage_stretch(soil.slip_sinkage, slip, soil.n) : 1.0;
  Contact c{r,
            b,
            slip,
            (soil.Kc / b + soil.Kphi) * std::pow(r / stretch, soil.n),
            soil.n,
            soil.cohesion,
            std::tan(soil.friction_deg * M_PI / 180.0),
            soil.janosi_k,
            options.shear_displacement,
            options.rear_stiffness,
            options.damping * options.carriage_speed,
            options.patch_width,
            soil.Kc,
            soil.Kphi,
            std::pow(r / stretch, soil.n),
            options.slip_sinkage && options.local_slip_sinkage ? &soil.slip_sinkage : nullptr};
  c.stretch_slip = stretch;
  Equilibrium eq{&c, &options, w.get(), load, nullptr};
  const double theta1 = solve_entry_angle(eq, options.rel_tol);

  set_entry_angle(c, theta1, options);
  if (c.patch_width && !(c.kc / c.patch_b + c.kphi > 0))
    throw RunError(fmt::format("wong_reece: Kc/b + Kphi = {:.4g} Pa/m^n <= 0 for the contact patch's Bekker "
                               "width b = {:.4g} m: the set's pressure-sinkage law has no strength there",
                               c.kc / c.patch_b + c.kphi, c.patch_b));
  WongReeceResult out;
  out.slip = slip;
  out.load = load;
  out.entry_angle = theta1;
  out.max_stress_angle = c.theta_m;
  out.sinkage = r * (1.0 - std::cos(theta1));
  out.vertical_force = r * b * integrate(c, Quantity::Vertical, options.rel_tol, w.get());
  out.dbp = r * b * integrate(c, Quantity::Drawbar, options.rel_tol, w.get());
  out.torque = r * r * b * integrate(c, Quantity::Torque, options.rel_tol, w.get());
  return out;
}

}  // namespace terracal::lowfi
