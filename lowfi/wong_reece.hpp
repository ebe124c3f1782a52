#pragma once
// The analytic Wong-Reece rigid wheel on a Bekker-Wong-Janosi soil (docs/architecture.md,
// "SCM and Wong-Reece").
// Sources: J.Y. Wong and A.R. Reece, "Prediction of rigid wheel performance based on the analysis of
// soil-wheel stresses", J. Terramechanics 4(1) and 4(2), 1967; J.Y. Wong, Theory of Ground Vehicles,
// 4th ed. (2008), chapter 5.
//
// Angles are measured from the vertical below the axle, positive toward the front; the soil leaves
// the wheel at theta2 = 0. The normal stress follows the Bekker law on the front part
// (theta_m <= theta <= theta1) and is mirrored onto the rear part (0 <= theta <= theta_m); the shear
// stress follows Janosi-Hanamoto with the shear displacement of a slipping rim.
//
// Two options put the model's stresses where SCM puts them, so that the two can be compared term by
// term (results/scm_vs_wong_reece): c1 = c2 = 0 is Bekker's classic wheel (peak stress at the
// bottom, no rear part), and ShearDisplacement::ground counts the shear as SCM does.
#include "lowfi/scm_soil.hpp"

namespace terracal::lowfi {

struct WongReeceWheel {
  double radius = 0.47;  // [m]
  double width = 0.25;   // [m]; the Bekker width b
};

// Whose shear displacement j(theta) the Janosi law sees.
enum class ShearDisplacement {
  // Wong-Reece: the slip of a point of the rim since it entered the soil, over the time (theta1 -
  // theta)/omega: j = r [(theta1 - theta) - (1 - s)(sin theta1 - sin theta)].
  rim,
  // SCM (and Chrono's): the slip accumulated by a point fixed in the ground while the contact passes
  // over it, over the time the carriage takes, r (sin theta1 - sin theta)/v:
  // j = r/(1 - s) [(sin theta1 - sin theta) - (1 - s)((theta1 - theta)/2 + (sin 2theta1 - sin 2theta)/4)].
  // 1/(1 - s) times the rim's for a shallow contact: a slower carriage leaves the rim longer over a point.
  ground,
};

struct WongReeceOptions {
  // theta_m = (c1 + c2 s) theta1, clamped to [0, theta1]. Wong-Reece's values for sand.
  double c1 = 0.43, c2 = 0.32;
  ShearDisplacement shear_displacement = ShearDisplacement::rim;
  // Relative tolerance of the entry-angle root and of each quadrature, in [1e-14, 1e-3].
  double rel_tol = 1e-9;
  // Slip sinkage (lowfi/slip_sinkage.hpp, the soil's S): the pressure-sinkage law stretched by the
  // wheel's slip, as the SCM effect slip_sinkage does per node. Off: the model as published.
  bool slip_sinkage = false;
  // SCM's own assumptions beyond the peak at the bottom (c1 = c2 = 0) and the ground's shear
  // displacement, for the steady SCM wheel (lowfi/scm_steady_wheel.hpp):
  // - rear_stiffness [Pa/m] > 0: behind the bottom the soil rebounds elastically against the rising
  //   rim, sigma = sigma(0) - Ke r (1 - cos theta), until it lets go (0: the rear carries nothing);
  // - damping [Pa s/m] at carriage_speed [m/s]: the front's pressure gains R v sin(theta), the
  //   damping effect's R v_n on a rim sinking into the soil.
  double rear_stiffness = 0, damping = 0, carriage_speed = 0;
  // - patch_width: the Bekker width b of Kc / b is SCM's 2 A / P of the contact patch (its length
  //   from the rear's end to the entry, across the wheel's width) instead of the wheel's width.
  bool patch_width = false;
  // - local_slip_sinkage: with slip_sinkage, the stretch at each rim angle from the slip the ground
  //   sees there, 1 - (1 - s) cos(theta) (SCM's per-node slip), not the wheel's s.
  bool local_slip_sinkage = false;
};

struct WongReeceResult {
  double slip = 0, load = 0;    // inputs echoed
  double entry_angle = 0;       // theta1 [rad]
  double max_stress_angle = 0;  // theta_m [rad]
  double sinkage = 0;           // z = r (1 - cos theta1) [m]
  double dbp = 0;               // drawbar pull [N] = r b ∫ (tau cos θ − sigma sin θ) dθ
  double torque = 0;            // driving torque [N m] = r^2 b ∫ tau dθ
  double vertical_force = 0;    // r b ∫ (sigma cos θ + tau sin θ) dθ [N], equals `load` at the solution
};

// Steady state of a rigid wheel carrying `load` [N] at slip s (−1 < s < 1; s = 1 − v/(ω r); s < 0 is
// skid). Throws InputError for bad arguments (non-positive radius/width/load, |s| >= 1, non-finite
// values, a soil outside its physical range, bad options) with a message naming the argument, its value
// and the allowed range; RunError if no entry angle in (0, π/2] carries the load (the wheel would sink
// past its axle) or a quadrature fails.
// Thread safety: calls are serialised process-wide while GSL's abort-on-error handler is switched off.
WongReeceResult wong_reece(const ScmSoil& soil, const WongReeceWheel& wheel, double load, double slip,
                           const WongReeceOptions& options = {});

}  // namespace terracal::lowfi
