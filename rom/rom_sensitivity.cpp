#include "rom/rom_sensitivity.hpp"

#include <cmath>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "rom/cvodes_integrator.hpp"
#include "rom/rom_models.hpp"

namespace terracal::rom {

namespace {

double* parameter_field(RomVehicle& v, const std::string& name) {
  if (name == "mass") return &v.mass;
  if (name == "cg_height") return &v.cg_height;
  if (name == "yaw_inertia") return &v.yaw_inertia;
  if (name == "roll_inertia") return &v.roll_inertia;
  if (name == "max_steer") return &v.max_steer;
  if (name == "friction") return &v.friction;
  if (name == "drag_area") return &v.drag_area;
  if (name == "roll_stiffness_front") return &v.roll_stiffness[0];
  if (name == "roll_stiffness_rear") return &v.roll_stiffness[1];
  if (name == "roll_damping_front") return &v.roll_damping[0];
  if (name == "roll_damping_rear") return &v.roll_damping[1];
  return nullptr;
}

template <class M>
void run(RomVehicle v, const DriverSeries& d, const RomRunOptions& o, const std::vector<std::string>& names,
         RomSensitivityResult& r) {
  // CVODES needs the parameters as one array it can perturb; the right-hand side reads them from a
  // vehicle copied back from that array on every call.
  std::vector<double> p, scale;
  std::vector<double*> fields;
  for (const auto& n : names) {
    fields.push_back(parameter_field(v, n));
    p.push_back(*fields.back());
    scale.push_back(std::max(std::fabs(*fields.back()), 1e-6));
  }
  double y[M::kStates];
  int gear = M::initial_state(v, o.initial_speed, y);
  CvodesProblem problem;
  problem.states = M::kStates;
  problem.rhs = [&](double t, const double* state, double* dy) {
    for (std::size_t k = 0; k < fields.size(); ++k) *fields[k] = p[k];
    RomAux aux;
    M::rhs(v, d.at(t), gear, state, dy, &aux, true);
  };
  CvodesIntegrator cv(problem, y, o.rtol, o.atol);
  // The initial state depends on some parameters (the wheels' spins on the static loads): its
  // derivative by central differences.
  std::vector<double> initial(p.size() * M::kStates);
  for (std::size_t k = 0; k < p.size(); ++k) {
    const double h = 1e-6 * scale[k];
    double up[M::kStates], down[M::kStates];
    *fields[k] = p[k] + h;
    M::initial_state(v, o.initial_speed, up);
    *fields[k] = p[k] - h;
    M::initial_state(v, o.initial_speed, down);
    *fields[k] = p[k];
    for (int i = 0; i < M::kStates; ++i) initial[k * M::kStates + i] = (up[i] - down[i]) / (2 * h);
  }
  cv.enable_sensitivities(p.data(), static_cast<int>(p.size()), scale.data(), initial.data());
  r.states = M::kStates;
  const std::size_t block = p.size() * M::kStates;
  auto record = [&](double t) {
    RomAux aux;
    double dy[M::kStates];
    M::rhs(v, d.at(t), gear, y, dy, &aux, true);
    r.samples.push_back(M::sample(v, t, y, aux, gear));
    r.dstate_dparam.resize(r.dstate_dparam.size() + block, 0.0);
    if (t > 0)
      cv.sensitivities(r.dstate_dparam.data() + r.dstate_dparam.size() - block);
    else
      std::copy(initial.begin(), initial.end(), r.dstate_dparam.end() - block);
    return aux;
  };
  record(0.0);
  const double dt = 1.0 / o.output_rate;
  const long samples = std::lround(o.end_time / dt);
  for (long k = 1; k <= samples; ++k) {
    cv.advance(k * dt, y);
    const RomAux aux = record(k * dt);
    const int new_gear = shift_gear(v.powertrain, gear, aux.gearbox_input_speed);
    if (new_gear != gear) {
      gear = new_gear;
      cv.restart(k * dt, y);
    }
  }
}

}  // namespace

const std::vector<std::string>& sensitivity_parameter_names() {
  static const std::vector<std::string> names = {"mass",
                                                 "cg_height",
                                                 "yaw_inertia",
                                                 "roll_inertia",
                                                 "max_steer",
                                                 "friction",
                                                 "drag_area",
                                                 "roll_stiffness_front",
                                                 "roll_stiffness_rear",
                                                 "roll_damping_front",
                                                 "roll_damping_rear"};
  return names;
}

RomSensitivityResult run_rom_sensitivities(const RomVehicle& vehicle, const DriverSeries& driver,
                                           const RomRunOptions& options, const std::vector<std::string>& parameters) {
  RomVehicle v = vehicle;
  for (const auto& n : parameters)
    if (!parameter_field(v, n))
      throw InputError(fmt::format("sensitivity parameter '{}': expected one of {}", n,
                                   fmt::join(sensitivity_parameter_names(), ", ")));
  check_model_effects(v, options.model);
  RomSensitivityResult r;
  r.parameters = parameters;
  with_model(options.model, [&](auto model) { run<decltype(model)>(v, driver, options, parameters, r); });
  return r;
}

}  // namespace terracal::rom
