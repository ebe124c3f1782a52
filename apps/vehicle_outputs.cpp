#include "apps/vehicle_outputs.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "highfi/vehicle/steering_kinematics.hpp"
#include "highfi/vehicle/vehicle_vtu.hpp"
#include "rom/trajectory_csv.hpp"

namespace terracal::app {

void write_vehicle_outputs(const std::string& out, const VehicleRunInfo& a, const vehicle::VehicleRunOptions& run,
                           const vehicle::VehicleRunResult& r) {
  std::vector<rom::RomSample> rows;
  for (const auto& s : r.samples)
    rows.push_back({s.time, s.x, s.y, s.z, s.yaw, s.roll, s.pitch, s.vx, s.vy, s.yaw_rate, s.roll_rate, s.ax, s.ay,
                    s.engine_speed_rpm, s.gear});
  rom::write_trajectory_csv(out + "/trajectory.csv", rows);
  std::string w = "time,wheel,fz_N,fx_N,fy_N,slip_x,slip_y,deflection_m,sinkage_m\n";
  for (const auto& s : r.wheels)
    w += fmt::format("{:.6g},{},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n", s.time, s.wheel, s.contact.fz,
                     s.contact.fx, s.contact.fy, s.contact.sx, s.contact.sy, s.contact.deflection, s.contact.sinkage);
  write_text_atomically(out + "/wheels.csv", w);
  // The inputs applied, as a driver file (DriverSeries::read gives them back exactly).
  std::string source = a.driver;
  std::replace_if(
      source.begin(), source.end(), [](char c) { return c == '\n' || c == '\r'; }, '?');  // one line
  std::string d = !a.from_inputs ? fmt::format(
                                         "# driver inputs of terracal vehicle --maneuver {}: at every control time "
                                         "and the end, linear between rows\n",
                                         source)
                                   : fmt::format("# driver inputs of terracal vehicle: the rows of {}\n", source);
  d += "# time steering throttle braking\n";
  for (const auto& k : r.inputs)
    d += fmt::format("{:.17g} {:.17g} {:.17g} {:.17g}\n", k.time, k.input.steering, k.input.throttle, k.input.braking);
  write_text_atomically(out + "/inputs.txt", d);
  nlohmann::json j = {{"model", "full multibody vehicle"},
                      {"integrator", "IDAS (GGL index 2)"},
                      {"vehicle", a.vehicle},
                      {"terrain", a.terrain},
                      {"end_time", run.end_time},
                      {"rtol", run.rtol},
                      {"steps", r.steps},
                      {"residuals", r.residuals},
                      {"max_constraint_violation", r.max_constraint_violation},
                      {"wall_seconds", r.wall_seconds},
                      {"real_time_factor", run.end_time / std::max(r.wall_seconds, 1e-12)}};
  if (run.soil) {
    std::vector<std::string> effects;  // those on, in the registry's order
    run.scm.effects.named.for_each_named([&](auto tag) { effects.push_back(decltype(tag)::type::kName); });
    j["scm"] = {{"soil", a.scm}, {"grid", run.scm.grid}, {"time_step", run.scm.time_step}, {"effects", effects}};
  }
  if (a.vtu)
    j["vtu"] = {{"collection", "vtu/vehicle.pvd"},
                {"rate_hz", run.vtu_rate},
                {"snapshots", r.vtu_snapshots},
                {"bodies", r.vtu_bodies},
                {"names", vehicle::kVehicleVtuNames}};
  write_text_atomically(out + "/run.json", j.dump(2) + "\n");
}

// The manoeuvres' view of the vehicle (vehicle_outputs.hpp).
ManeuverVehicle maneuver_vehicle(const vehicle::FullVehicleSpec& spec) {
  if (!spec.has_steering) throw InputError("--maneuver: the vehicle has no steering; drive it with --inputs");
  const vehicle::SteerAngles lock =
      vehicle::steering_kinematics(spec, {vehicle::steering_position(spec, 1.0)})[0];  // full left
  const double track = 2 * std::abs(spec.axles.front().suspension.spindle.com.y());
  return {spec.axles.front().location.x() - spec.axles.back().location.x(), 0.5 * (lock.left + lock.right), track};
}

}  // namespace terracal::app
