#include "highfi/multibody/mb_integrator.hpp"

#include <idas/idas.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "highfi/multibody/ggl_jacobian.hpp"
#include "highfi/multibody/ggl_residual.hpp"

namespace terracal::mb {
namespace {
using Eigen::VectorXd;

// The positions moved by eps along the motion with velocities u (body-frame angular velocity held).
void move_along(MbSystem& s, const VectorXd& q0, const VectorXd& u, double eps) {
  s.set_positions(q0.data());
  for (std::size_t b = 0, k = 0; b < s.bodies.size(); ++b) {
    if (s.bodies[b].fixed) continue;
    RigidBody& body = s.bodies[b];
    const Vec3 w = u.segment<3>(Eigen::Index(6 * k + 3)) * eps;
    body.position += u.segment<3>(Eigen::Index(6 * k)) * eps;
    if (w.norm() > 0) body.orientation = body.orientation * Quat(Eigen::AngleAxisd(w.norm(), w.normalized()));
    ++k;
  }
}
}  // namespace

struct MbIntegrator::Impl {
  MbSystem& sys;
  int nq = 0, nu = 0, m = 0, mh = 0, nb = 0, size = 0;  // m all constraint rows, mh the position ones
  SUNContext context = nullptr;
  N_Vector yy = nullptr, yp = nullptr, ids = nullptr, atol = nullptr;
  SUNMatrix matrix = nullptr;
  SUNLinearSolver solver = nullptr;
  void* mem = nullptr;
  double t = 0;
  bool stopped = false;  // the last advance set a stop time
  Eigen::MatrixXd mass;
  std::unique_ptr<GglJacobian> jacobian;  // null: IDAS's dense difference quotients
  MbIntegratorStats before;               // counts of the runs before the last restart (IDAReInit zeroes IDAS's)

  explicit Impl(MbSystem& s) : sys(s) {}

  void check(int flag, const char* call) const {
    if (flag < 0) throw RunError(fmt::format("multibody: IDAS {} failed at t = {:.6g} s (flag {})", call, t, flag));
  }

  static int res(sunrealtype time, N_Vector y, N_Vector yd, N_Vector r, void* user) {
    Impl& s = *static_cast<Impl*>(user);
    // A non-finite force or constraint is a recoverable failure: IDAS retries with a smaller step.
    return ggl_residual(s.sys, s.mass, time, N_VGetArrayPointer(y), N_VGetArrayPointer(yd), N_VGetArrayPointer(r)) ? 0
                                                                                                                   : 1;
  }

  // The sparse Newton matrix, copied into IDAS's compressed-column matrix (same pattern every time).
  static int jac(sunrealtype time, sunrealtype cj, N_Vector y, N_Vector, N_Vector, SUNMatrix out, void* user, N_Vector,
                 N_Vector, N_Vector) {
    Impl& s = *static_cast<Impl*>(user);
    const Eigen::SparseMatrix<double>& j = s.jacobian->evaluate(time, N_VGetArrayPointer(y), cj);
    if (j.nonZeros() != SM_NNZ_S(out)) return -1;  // the pattern is fixed
    if (!Eigen::Map<const VectorXd>(j.valuePtr(), j.nonZeros()).allFinite()) return 1;
    std::copy(j.outerIndexPtr(), j.outerIndexPtr() + j.outerSize() + 1, SM_INDEXPTRS_S(out));
    std::copy(j.innerIndexPtr(), j.innerIndexPtr() + j.nonZeros(), SM_INDEXVALS_S(out));
    std::copy(j.valuePtr(), j.valuePtr() + j.nonZeros(), SM_DATA_S(out));
    // New pivots for every new matrix: KLU would otherwise factor it with the first matrix's pivot
    // order, which fails when cj changes by orders of magnitude (the step shrinking at an impact); a
    // fresh order costs no more than the extra Newton iterations of a stale one (measured on the HMMWV).
    SUNLinSol_KLUReInit(s.solver, out, SM_NNZ_S(out), SUNKLU_REINIT_PARTIAL);
    return 0;
  }

  // Consistent initial values: assembled positions and velocities, then accelerations and lambda from
  // [M J^T; J 0] [a; lambda] = [f; -J' u], J' u by a central difference along the motion.
  void initial_values(double t0, double* y, double* ydot) {
    sys.assemble();
    VectorXd q(nq), u(nu);
    sys.get_positions(q.data());
    sys.get_velocities(u.data());
    VectorXd phi;
    Eigen::MatrixXd jac, jp, jm;
    const double eps = 1e-5 / std::max(1.0, u.lpNorm<Eigen::Infinity>());
    move_along(sys, q, u, eps);
    sys.constraints(phi, jp);
    move_along(sys, q, u, -eps);
    sys.constraints(phi, jm);
    sys.set_positions(q.data());
    sys.constraints(phi, jac);
    const VectorXd gamma = -(jp - jm) * u / (2 * eps);
    Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(nu + m, nu + m);
    kkt.topLeftCorner(nu, nu) = mass;
    kkt.topRightCorner(nu, m) = jac.transpose();
    kkt.bottomLeftCorner(m, nu) = jac;
    VectorXd rhs(nu + m);
    rhs << sys.applied(t0), gamma;
    const VectorXd sol = kkt.partialPivLu().solve(rhs);
    Eigen::Map<VectorXd>(y, size).setZero();
    Eigen::Map<VectorXd>(ydot, size).setZero();
    Eigen::Map<VectorXd>(y, nq) = q;
    Eigen::Map<VectorXd>(y + nq, nu) = u;
    Eigen::Map<VectorXd>(y + nq + nu, m) = sol.tail(m);
    sys.coordinate_rates(q.data(), u.data(), ydot);
    Eigen::Map<VectorXd>(ydot + nq, nu) = sol.head(nu);
  }
};

MbIntegrator::MbIntegrator(MbSystem& system, MbIntegratorOptions o, double t0) : impl_(std::make_unique<Impl>(system)) {
  Impl& s = *impl_;
  system.index();
  s.t = t0;
  s.nb = system.moving();
  s.nq = system.coordinates();
  s.nu = system.velocities();
  s.m = system.constraint_rows();
  s.mh = system.position_rows();
  s.size = s.nq + s.nu + s.m + s.mh + s.nb;
  s.mass = system.mass_matrix();
  s.check(SUNContext_Create(nullptr, &s.context), "SUNContext_Create");
  s.yy = N_VNew_Serial(s.size, s.context);
  s.yp = N_VNew_Serial(s.size, s.context);
  s.ids = N_VNew_Serial(s.size, s.context);
  s.atol = N_VNew_Serial(s.size, s.context);
  s.initial_values(t0, N_VGetArrayPointer(s.yy), N_VGetArrayPointer(s.yp));
  for (int k = 0; k < s.size; ++k) {
    const bool differential = k < s.nq + s.nu;
    NV_Ith_S(s.ids, k) = differential ? 1.0 : 0.0;
    NV_Ith_S(s.atol, k) = differential ? o.atol : 1e30;  // multipliers are not in the error test
  }
  s.mem = IDACreate(s.context);
  s.check(IDAInit(s.mem, Impl::res, t0, s.yy, s.yp), "IDAInit");
  s.check(IDASVtolerances(s.mem, o.rtol, s.atol), "IDASVtolerances");
  s.check(IDASetUserData(s.mem, &s), "IDASetUserData");
  s.check(IDASetId(s.mem, s.ids), "IDASetId");
  s.check(IDASetSuppressAlg(s.mem, SUNTRUE), "IDASetSuppressAlg");
  if (o.jacobian == MbIntegratorOptions::Jacobian::sparse) {
    s.jacobian = std::make_unique<GglJacobian>(system);
    const Eigen::Index nnz = s.jacobian->evaluate(t0, N_VGetArrayPointer(s.yy), 1.0).nonZeros();
    s.matrix = SUNSparseMatrix(s.size, s.size, nnz, CSC_MAT, s.context);
    s.solver = SUNLinSol_KLU(s.yy, s.matrix, s.context);
    s.check(SUNLinSol_KLUSetOrdering(s.solver, 0), "SUNLinSol_KLUSetOrdering");  // AMD: the fastest here
    s.check(IDASetLinearSolver(s.mem, s.solver, s.matrix), "IDASetLinearSolver");
    s.check(IDASetJacFn(s.mem, Impl::jac), "IDASetJacFn");
  } else {
    s.matrix = SUNDenseMatrix(s.size, s.size, s.context);
    s.solver = SUNLinSol_Dense(s.yy, s.matrix, s.context);
    s.check(IDASetLinearSolver(s.mem, s.solver, s.matrix), "IDASetLinearSolver");
  }
  s.check(IDASetMaxNumSteps(s.mem, 10000000), "IDASetMaxNumSteps");
  if (o.max_step > 0) s.check(IDASetMaxStep(s.mem, o.max_step), "IDASetMaxStep");
}

MbIntegrator::~MbIntegrator() {
  Impl& s = *impl_;
  IDAFree(&s.mem);
  SUNLinSolFree(s.solver);
  SUNMatDestroy(s.matrix);
  N_VDestroy(s.yy);
  N_VDestroy(s.yp);
  N_VDestroy(s.ids);
  N_VDestroy(s.atol);
  SUNContext_Free(&s.context);
}

void MbIntegrator::advance(double t_out, bool stop) {
  Impl& s = *impl_;
  if (t_out > s.t) {
    // A stop time far ahead lifts an earlier one (IDAS keeps the last one set).
    if (stop || s.stopped) s.check(IDASetStopTime(s.mem, stop ? t_out : 1e300), "IDASetStopTime");
    s.stopped = stop;
    s.check(IDASolve(s.mem, t_out, &s.t, s.yy, s.yp, IDA_NORMAL), "IDASolve");
  }
  s.sys.set_positions(N_VGetArrayPointer(s.yy));
  s.sys.set_velocities(N_VGetArrayPointer(s.yy) + s.nq);
}

void MbIntegrator::reinitialize() {
  Impl& s = *impl_;
  s.before = stats();
  s.initial_values(s.t, N_VGetArrayPointer(s.yy), N_VGetArrayPointer(s.yp));
  s.check(IDAReInit(s.mem, s.t, s.yy, s.yp), "IDAReInit");
}

double MbIntegrator::time() const { return impl_->t; }

Eigen::VectorXd MbIntegrator::accelerations() const {
  const Impl& s = *impl_;
  return Eigen::Map<const VectorXd>(N_VGetArrayPointer(s.yp) + s.nq, s.nu);
}

double MbIntegrator::constraint_violation() const {
  const Impl& s = *impl_;
  VectorXd phi;
  Eigen::MatrixXd jac;
  s.sys.constraints(phi, jac);
  double worst = phi.size() ? phi.lpNorm<Eigen::Infinity>() : 0.0;
  const double* y = N_VGetArrayPointer(s.yy);
  for (int k = 0; k < s.nb; ++k)
    worst = std::max(worst, std::abs(Eigen::Map<const Eigen::Vector4d>(y + 7 * k + 3).norm() - 1));
  return worst;
}

Wrench MbIntegrator::reaction(int joint, int body) const {
  const Impl& s = *impl_;
  const Joint& jt = s.sys.joints.at(std::size_t(joint));
  if (body != jt.i && body != jt.j)
    throw InputError(fmt::format("multibody: body {} is not in joint '{}'", body, jt.name));
  if (s.sys.bodies[std::size_t(body)].fixed) throw InputError("multibody: a fixed body's reaction is not computed");
  int row0 = 0, slot = 0;
  for (int k = 0; k < joint; ++k) row0 += joint_rows(s.sys.joints[std::size_t(k)].type);
  for (int b = 0; b < body; ++b) slot += s.sys.bodies[std::size_t(b)].fixed ? 0 : 1;
  const int rows = joint_rows(jt.type);
  VectorXd phi;
  Eigen::MatrixXd jac;
  s.sys.constraints(phi, jac);
  const Eigen::Map<const VectorXd> lambda(N_VGetArrayPointer(s.yy) + s.nq + s.nu + row0, rows);
  const VectorXd w = -jac.block(row0, 6 * slot, rows, 6).transpose() * lambda;
  return {w.head<3>(), w.tail<3>()};
}

MbIntegratorStats MbIntegrator::stats() const {
  const Impl& s = *impl_;
  MbIntegratorStats st;
  IDAGetNumSteps(s.mem, &st.steps);
  IDAGetNumResEvals(s.mem, &st.residuals);
  IDAGetNumJacEvals(s.mem, &st.jacobians);
  IDAGetNumErrTestFails(s.mem, &st.error_test_failures);
  IDAGetNumNonlinSolvConvFails(s.mem, &st.newton_failures);
  st.steps += s.before.steps;
  st.residuals += s.before.residuals;
  st.jacobians += s.before.jacobians;
  st.error_test_failures += s.before.error_test_failures;
  st.newton_failures += s.before.newton_failures;
  return st;
}

}  // namespace terracal::mb
