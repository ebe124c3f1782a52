#pragma once
// SUNDIALS CVODES (BDF, Newton with a dense linear solver) behind a small interface: a right-hand
// side dy = f(t, y) of fixed size, advanced to given times, restarted where the model changes
// discontinuously (a gear shift, a new held input).
#include <functional>
#include <memory>

namespace terracal::rom {

struct CvodesProblem {
  int states = 0;
  std::function<void(double t, const double* y, double* dy)> rhs;
};

class CvodesIntegrator {
 public:
  CvodesIntegrator(CvodesProblem problem, const double* y0, double rtol, double atol);
  ~CvodesIntegrator();
  CvodesIntegrator(const CvodesIntegrator&) = delete;
  CvodesIntegrator& operator=(const CvodesIntegrator&) = delete;
  // Integrates to t_out and writes the state there. Throws RunError when CVODES fails.
  void advance(double t_out, double* y);
  // Starts again from (t, y), discarding the solver's history (sensitivities carry over).
  void restart(double t, const double* y);
  // Forward sensitivities dy/dp of every state with respect to `count` parameters that the
  // right-hand side reads through `params` (CVODES perturbs them in place for its difference
  // quotients); `scales` are their typical magnitudes. Call before the first advance.
  // `initial`: dy0/dp, [parameter][state] (the initial state may depend on the parameters).
  void enable_sensitivities(double* params, int count, const double* scales, const double* initial);
  // dy/dp at the last advance time: [parameter][state].
  void sensitivities(double* out) const;
  long steps() const;
  long rhs_evaluations() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace terracal::rom
