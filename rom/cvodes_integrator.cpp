#include "rom/cvodes_integrator.hpp"

#include <cvodes/cvodes.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <fmt/format.h>

#include "core/errors.hpp"

namespace terracal::rom {

struct CvodesIntegrator::Impl {
  CvodesProblem problem;
  SUNContext context = nullptr;
  N_Vector y = nullptr;
  SUNMatrix matrix = nullptr;
  SUNLinearSolver solver = nullptr;
  void* mem = nullptr;
  double t = 0;
  long steps = 0, rhs_evaluations = 0;  // summed over restarts
  int sens_count = 0;
  N_Vector* sens = nullptr;

  static int rhs(sunrealtype t, N_Vector y, N_Vector dy, void* user) {
    auto* self = static_cast<Impl*>(user);
    self->problem.rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(dy));
    return 0;
  }
  void check(int flag, const char* call) const {
    if (flag < 0) throw RunError(fmt::format("rom: CVODES {} failed at t = {:.6g} s (flag {})", call, t, flag));
  }
  void count() {
    long n = 0;
    CVodeGetNumSteps(mem, &n);
    steps += n;
    CVodeGetNumRhsEvals(mem, &n);
    rhs_evaluations += n;
  }
};

CvodesIntegrator::CvodesIntegrator(CvodesProblem problem, const double* y0, double rtol, double atol)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.problem = std::move(problem);
  m.check(SUNContext_Create(nullptr, &m.context), "SUNContext_Create");
  m.y = N_VNew_Serial(m.problem.states, m.context);
  for (int i = 0; i < m.problem.states; ++i) NV_Ith_S(m.y, i) = y0[i];
  m.mem = CVodeCreate(CV_BDF, m.context);
  m.check(CVodeInit(m.mem, Impl::rhs, 0.0, m.y), "CVodeInit");
  m.check(CVodeSStolerances(m.mem, rtol, atol), "CVodeSStolerances");
  m.check(CVodeSetUserData(m.mem, &m), "CVodeSetUserData");
  m.matrix = SUNDenseMatrix(m.problem.states, m.problem.states, m.context);
  m.solver = SUNLinSol_Dense(m.y, m.matrix, m.context);
  m.check(CVodeSetLinearSolver(m.mem, m.solver, m.matrix), "CVodeSetLinearSolver");
  m.check(CVodeSetMaxNumSteps(m.mem, 1000000), "CVodeSetMaxNumSteps");
}

CvodesIntegrator::~CvodesIntegrator() {
  Impl& m = *impl_;
  if (m.sens) N_VDestroyVectorArray(m.sens, m.sens_count);
  CVodeFree(&m.mem);
  SUNLinSolFree(m.solver);
  SUNMatDestroy(m.matrix);
  N_VDestroy(m.y);
  SUNContext_Free(&m.context);
}

void CvodesIntegrator::advance(double t_out, double* y) {
  Impl& m = *impl_;
  m.check(CVode(m.mem, t_out, m.y, &m.t, CV_NORMAL), "CVode");
  for (int i = 0; i < m.problem.states; ++i) y[i] = NV_Ith_S(m.y, i);
}

void CvodesIntegrator::restart(double t, const double* y) {
  Impl& m = *impl_;
  m.count();
  if (m.sens) {
    double tt = 0;
    m.check(CVodeGetSens(m.mem, &tt, m.sens), "CVodeGetSens");
  }
  for (int i = 0; i < m.problem.states; ++i) NV_Ith_S(m.y, i) = y[i];
  m.t = t;
  m.check(CVodeReInit(m.mem, t, m.y), "CVodeReInit");
  if (m.sens) m.check(CVodeSensReInit(m.mem, CV_STAGGERED, m.sens), "CVodeSensReInit");
}

void CvodesIntegrator::enable_sensitivities(double* params, int count, const double* scales, const double* initial) {
  Impl& m = *impl_;
  m.sens_count = count;
  m.sens = N_VCloneVectorArray(count, m.y);
  for (int k = 0; k < count; ++k)
    for (int i = 0; i < m.problem.states; ++i) NV_Ith_S(m.sens[k], i) = initial[k * m.problem.states + i];
  m.check(CVodeSensInit1(m.mem, count, CV_STAGGERED, nullptr, m.sens), "CVodeSensInit1");
  m.check(CVodeSetSensParams(m.mem, params, const_cast<double*>(scales), nullptr), "CVodeSetSensParams");
  m.check(CVodeSensEEtolerances(m.mem), "CVodeSensEEtolerances");
  // The states' error test sets the steps; the sensitivities ride along (with the error test on them
  // too, their absolute tolerances atol / |p| for parameters of order 1e3 stall tight runs).
  m.check(CVodeSetSensErrCon(m.mem, SUNFALSE), "CVodeSetSensErrCon");
}

void CvodesIntegrator::sensitivities(double* out) const {
  Impl& m = *impl_;
  double t = 0;
  m.check(CVodeGetSens(m.mem, &t, m.sens), "CVodeGetSens");
  for (int k = 0; k < m.sens_count; ++k)
    for (int i = 0; i < m.problem.states; ++i) out[k * m.problem.states + i] = NV_Ith_S(m.sens[k], i);
}

long CvodesIntegrator::steps() const {
  long n = 0;
  CVodeGetNumSteps(impl_->mem, &n);
  return impl_->steps + n;
}
long CvodesIntegrator::rhs_evaluations() const {
  long n = 0;
  CVodeGetNumRhsEvals(impl_->mem, &n);
  return impl_->rhs_evaluations + n;
}

}  // namespace terracal::rom
