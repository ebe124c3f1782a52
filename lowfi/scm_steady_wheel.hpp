#pragma once
// The steady SCM wheel: the rigid-wheel integrals under SCM's own assumptions, a forward model of
// microseconds where the time-stepping SCM wheel takes a second per slip. SCM's node law gives, for
// a wheel rolling at steady slip:
// - in front of the bottom, Bekker's pressure of the rim's depth (the nodes yield as the rim sinks
//   them), the peak at the bottom (Wong-Reece's c1 = c2 = 0), plus the damping effect's R v sin(theta);
// - behind it, the soil springing back elastically (Ke) against the rising rim until it lets go;
// - Janosi shear from the slip each ground point has seen while the contact passed over it;
// - Kc over the contact patch's Bekker width 2 A / P, as SCM takes it, not over the wheel's width;
// - with the effect slip_sinkage, the pressure-sinkage law stretched by the slip the ground sees
//   under each point of the rim, 1 - (1 - s) cos(theta), as SCM's nodes do.
// Built on the Wong-Reece quadrature (lowfi/wong_reece.hpp) with those options; within 3 % of the
// time-stepping wheel on the reference soils (tests/lowfi/test_scm_steady_wheel.cpp).
#include "lowfi/wong_reece.hpp"

namespace terracal::lowfi {

struct ScmSteadyWheelOptions {
  double angular_velocity = 1.0;  // [rad/s] the carriage moves at omega r (1 - s)
  bool damping = true;            // SCM effect damping (the rigs' default)
  bool slip_sinkage = false;      // SCM effect slip_sinkage
  double rel_tol = 1e-7;          // the entry angle and the quadratures
};

inline WongReeceOptions scm_steady_options(const ScmSoil& soil, const WongReeceWheel& wheel, double slip,
                                           const ScmSteadyWheelOptions& o) {
  WongReeceOptions w;
  w.c1 = w.c2 = 0;
  w.shear_displacement = ShearDisplacement::ground;
  w.rel_tol = o.rel_tol;
  w.slip_sinkage = o.slip_sinkage;
  w.rear_stiffness = soil.elastic_stiffness;
  w.damping = o.damping ? soil.damping : 0.0;
  w.carriage_speed = std::abs(o.angular_velocity) * wheel.radius * (1 - slip);
  w.patch_width = true;
  w.local_slip_sinkage = true;
  return w;
}

// The steady wheel at slip s (0 <= s < 1) under `load` [N]: DBP, torque and sinkage as the rig's.
inline WongReeceResult scm_steady_wheel(const ScmSoil& soil, const WongReeceWheel& wheel, double load, double slip,
                                        const ScmSteadyWheelOptions& o = {}) {
  return wong_reece(soil, wheel, load, slip, scm_steady_options(soil, wheel, slip, o));
}

}  // namespace terracal::lowfi
