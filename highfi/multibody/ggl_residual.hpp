#pragma once
// The GGL residual of a multibody system (the equations in mb_integrator.hpp), for unknowns
// y = [q | u | lambda | mu | mu_n] and their rates y'; rows [kinematics | momentum | Phi | quaternion
// norms | Phi_v u]. One source for the integrator and for the tests of its Newton matrix.
#include "highfi/multibody/mb_system.hpp"

namespace terracal::mb {

// Leaves the system in the state y. Returns false when a force or a constraint value is not finite
// (the integrator then retries with a smaller step).
bool ggl_residual(MbSystem& s, const Eigen::MatrixXd& mass, double t, const double* y, const double* ydot, double* r);

// The number of unknowns of the GGL form.
inline int ggl_size(const MbSystem& s) {
  return s.coordinates() + s.velocities() + s.constraint_rows() + s.position_rows() + s.moving();
}

}  // namespace terracal::mb
