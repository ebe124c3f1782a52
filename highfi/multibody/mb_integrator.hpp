#pragma once
// Integrates a multibody system's equations of motion as a DAE with SUNDIALS IDAS, in the stabilized
// index-2 form of Gear, Gupta and Leimkuhler (GGL): unknowns the coordinates q, the velocities u, the
// multipliers lambda of the velocity constraints and mu of the position constraints,
//   q' = H(q) (u + Phi_v^T mu_j) + q mu_n     (mu is zero on the exact solution: it projects q' so
//   M u' = f(q, u, t) - Phi_v^T lambda         that the position constraints hold too)
//   0 = Phi(q), 0 = (|q|^2 - 1) / 2 per body,  0 = Phi_v(q) u,
// where Phi are the joints' position constraints and Phi_v u holds their velocity form and the shafts'
// couplings (velocity constraints only, with a lambda and no mu).
// Before the run, positions, velocities, accelerations and lambda are made consistent
// (MbSystem::assemble, then the acceleration-level saddle system): IDACalcIC alone cannot do this
// here, since the algebraic equations do not contain the algebraic unknowns.
#include <memory>

#include "highfi/multibody/mb_system.hpp"

namespace terracal::mb {

struct MbIntegratorOptions {
  double rtol = 1e-8;
  double atol = 1e-10;  // on positions (m, quaternion) and velocities (m/s, rad/s)
  double max_step = 0;  // s; 0: IDAS chooses
  // The Newton matrix: sparse (ggl_jacobian.hpp, factored by KLU), or IDAS's own difference quotients
  // of the whole residual, factored dense (one residual per unknown and a dense LU per Jacobian: for
  // comparison, and for systems of a few bodies).
  enum class Jacobian { sparse, dense_difference };
  Jacobian jacobian = Jacobian::sparse;
};

struct MbIntegratorStats {
  long steps = 0, residuals = 0, jacobians = 0, error_test_failures = 0, newton_failures = 0;
};

class MbIntegrator {
 public:
  MbIntegrator(MbSystem& system, MbIntegratorOptions options = {}, double t0 = 0);
  ~MbIntegrator();
  MbIntegrator(const MbIntegrator&) = delete;
  MbIntegrator& operator=(const MbIntegrator&) = delete;

  // Integrates to t and leaves the system's bodies in the state at t. With `stop`, no step goes past
  // t (an applied force changes there: a held soil wrench, a controller's new input); without, IDAS
  // may step past t and interpolate back.
  void advance(double t, bool stop = false);
  // Starts again from the system's present state (after a discrete change: a gear shift changes a
  // coupling's ratio): velocities projected onto the constraints, accelerations and multipliers
  // recomputed.
  void reinitialize();
  double time() const;
  // The velocities' rates at the present time (the integrator's own, consistent with the state): per
  // moving body the linear acceleration (world) and the angular one (body frame), then the shafts'.
  Eigen::VectorXd accelerations() const;
  // The largest constraint error now (joints' rows, m or rad-like; quaternion norms).
  double constraint_violation() const;
  // The reaction of joint k on one of its two bodies, a moving one (world force, torque in that body's
  // frame about its centre of mass): -Phi_v^T lambda over the joint's rows.
  Wrench reaction(int joint, int body) const;
  MbIntegratorStats stats() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace terracal::mb
