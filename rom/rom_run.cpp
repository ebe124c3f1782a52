#include "rom/rom_run.hpp"

#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "rom/cvodes_integrator.hpp"
#include "rom/half_implicit.hpp"
#include "rom/rom11.hpp"
#include "rom/rom18.hpp"
#include "rom/rom24.hpp"
#include "rom/rom_models.hpp"

namespace terracal::rom {

const char* model_name(RomModel m) {
  return m == RomModel::k11Dof ? Rom11::kName : m == RomModel::k18Dof ? Rom18::kName : Rom24::kName;
}
const char* integrator_name(RomIntegrator i) { return i == RomIntegrator::kCvodes ? "cvodes" : "half-implicit"; }

void check_model_effects(const RomVehicle& v, RomModel m) {
  if (v.has(kEffectDeformableTerrain) && !v.terrain.present())
    throw InputError(
        "effect 'deformable_terrain' takes its tire forces from a wheel table: give one (--terrain-table T.h5, "
        "from terracal wheel-table)");
  if (m == RomModel::k24Dof) {
    if (!(v.spring_rate[0] > 0 && v.spring_rate[1] > 0 && v.pitch_inertia > 0))
      throw InputError(
          "the 24-DOF model needs the vehicle's 'spring_rate', 'damper_rate' (per axle) and "
          "'pitch_inertia'");
    return;
  }
  if (v.has(kEffectSuspension))
    throw InputError(
        fmt::format("effect 'suspension' needs vertical travel per corner (the 24-DOF model); the {} "
                    "model has none: remove it from the vehicle's effects",
                    model_name(m)));
}

namespace {

template <class M>
DriverInput driver_input(RomDriver& d, double t, const double* y) {
  if (d.series) return d.series->at(t);
  return d.maneuver->at(VehiclePose{t, y[M::kX], y[M::kY], y[M::kYaw], y[M::kVx]});
}

template <class M>
RomSample sample_at(const RomVehicle& v, const DriverInput& in, int gear, double t, const double* y) {
  double dy[M::kStates];
  RomAux aux;
  M::rhs(v, in, gear, y, dy, &aux, true);
  return M::sample(v, t, y, aux, gear);
}

template <class M>
void run_half_implicit(const RomVehicle& v, RomDriver& d, const RomRunOptions& o, RomRunResult& r) {
  double y[M::kStates];
  int gear = M::initial_state(v, o.initial_speed, y);
  const double h = o.step, dt_out = 1.0 / o.output_rate;
  const long steps = std::lround(o.end_time / h);
  const long control_every = d.series ? 1 : std::max(1L, std::lround(d.control_period / h));
  DriverInput in = driver_input<M>(d, 0.0, y);
  // A sample at time t takes ax and ay from the right-hand side at t with the inputs from t on: the
  // next step's (the batch takes them from that step and saves a right-hand side per sample).
  double next_out = dt_out, pending = 0.0;  // the pending sample's time; < 0: none
  const auto take_pending = [&](const double* ys, const RomAux& a) {
    if (pending < 0) return;
    r.samples.push_back(M::sample(v, pending, ys, a, gear));
    pending = -1.0;
  };
  RomAux aux;
  for (long k = 0; k < steps; ++k) {
    const double t = k * h;
    if (k % control_every == 0) {
      in = driver_input<M>(d, t, y);
      if (!d.series) r.held_inputs.emplace_back(t, in);
    }
    if (!half_implicit_step<M>(v, in, gear, y, h, &aux, OneLanePerVehicle{}, take_pending))
      throw RunError(
          fmt::format("rom: the half-implicit scheme diverged at t = {:.4g} s with --step {} s: the step is "
                      "too large for this vehicle and manoeuvre; use a smaller --step or --integrator cvodes",
                      t + h, h));
    ++r.steps;
    const double t1 = (k + 1) * h;
    if (t1 >= next_out - 1e-9 * h) {
      pending = t1;
      next_out += dt_out;
    }
  }
  if (pending >= 0) {  // the last sample: the inputs at the end (a manoeuvre's held ones between its control times)
    const double t_end = steps * h;
    if (d.series || steps % control_every == 0) in = driver_input<M>(d, t_end, y);
    r.samples.push_back(sample_at<M>(v, in, gear, pending, y));
  }
  r.rhs_evaluations = r.steps;
}

template <class M>
void run_cvodes(const RomVehicle& v, RomDriver& d, const RomRunOptions& o, RomRunResult& r) {
  double y[M::kStates];
  int gear = M::initial_state(v, o.initial_speed, y);
  DriverInput held = driver_input<M>(d, 0.0, y);
  CvodesProblem problem;
  problem.states = M::kStates;
  problem.rhs = [&](double t, const double* state, double* dy) {
    RomAux aux;
    const DriverInput in = d.series ? d.series->at(t) : held;
    M::rhs(v, in, gear, state, dy, &aux, true);
  };
  CvodesIntegrator cv(problem, y, o.rtol, o.atol);
  r.samples.push_back(sample_at<M>(v, held, gear, 0.0, y));
  if (!d.series) r.held_inputs.emplace_back(0.0, held);
  // Chunks end at output times and, with a manoeuvre, at control times: the inputs and the gear
  // change only there (the solver restarts when they do).
  const double dt_out = 1.0 / o.output_rate;
  const double chunk = d.series ? dt_out : std::min(dt_out, d.control_period);
  const long chunks = std::lround(o.end_time / chunk);
  const long out_every = std::max(1L, std::lround(dt_out / chunk));
  for (long k = 1; k <= chunks; ++k) {
    const double t = k * chunk;
    cv.advance(t, y);
    const DriverInput in = d.series ? d.series->at(t) : held;
    if (k % out_every == 0) r.samples.push_back(sample_at<M>(v, in, gear, t, y));
    RomAux aux;
    double dy[M::kStates];
    M::rhs(v, in, gear, y, dy, &aux, true);
    const int new_gear = shift_gear(v.powertrain, gear, aux.gearbox_input_speed);
    bool restart = new_gear != gear;
    gear = new_gear;
    if (!d.series) {
      held = driver_input<M>(d, t, y);
      if (t < o.end_time - 1e-9 * chunk) r.held_inputs.emplace_back(t, held);
      restart = true;
    }
    if (restart) cv.restart(t, y);
  }
  r.steps = cv.steps();
  r.rhs_evaluations = cv.rhs_evaluations();
}

template <class M>
void run_model(const RomVehicle& v, RomDriver& d, const RomRunOptions& o, RomRunResult& r) {
  if (o.integrator == RomIntegrator::kCvodes)
    run_cvodes<M>(v, d, o, r);
  else
    run_half_implicit<M>(v, d, o, r);
}

}  // namespace

RomRunResult run_rom(const RomVehicle& vehicle, RomDriver& driver, const RomRunOptions& options) {
  check_model_effects(vehicle, options.model);
  RomRunResult r;
  const auto start = std::chrono::steady_clock::now();
  with_model(options.model, [&](auto model) { run_model<decltype(model)>(vehicle, driver, options, r); });
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace terracal::rom
