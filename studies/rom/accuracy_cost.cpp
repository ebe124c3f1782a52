// Accuracy against cost of the reduced-order vehicles: each model (11, 18, 24 DOF) with each
// integrator (half-implicit at several steps, CVODES at several tolerances) on a double lane change
// (ISO 3888-1 at 15 m/s, the path follower closing the loop) and a step steer (ISO 7401 at 20 m/s),
// against a tight CVODES run of the 24-DOF model (rtol 1e-10). Errors: the RMS of the yaw-rate and
// lateral-acceleration differences relative to the reference's RMS, and the largest path
// deviation; next to the wall time (median of 3 runs, one core).
// Usage: rom_accuracy_cost OUT_DIR   (writes accuracy_cost.csv and table.md; plot.sh draws the PNG)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "rom/rom_run.hpp"
#include "rom/rom_vehicle_json.hpp"

using namespace terracal;
using namespace terracal::rom;

namespace {

struct Case {
  std::string name;
  nlohmann::json maneuver;
};

struct Config {
  RomModel model;
  RomIntegrator integrator;
  double knob;  // step [s] or rtol
};

RomRunResult run_case(const RomVehicle& v, const Case& c, const Config& k) {
  const ManeuverVehicle mv{v.wheelbase(), v.max_steer, std::max(v.track[0], v.track[1])};
  Maneuver m = Maneuver::from_json(c.maneuver, c.name, mv);
  RomDriver d;
  d.maneuver = &m;
  d.control_period = 0.01;
  RomRunOptions o;
  o.model = k.model;
  o.integrator = k.integrator;
  if (k.integrator == RomIntegrator::kHalfImplicit) {
    o.step = k.knob;
  } else {
    o.rtol = k.knob;
    o.atol = k.knob * 1e-2;
  }
  o.end_time = m.end_time();
  o.initial_speed = m.initial_speed();
  return run_rom(v, d, o);
}

struct Errors {
  double yaw_rate = 0, ay = 0, path = 0;
};
Errors errors(const RomRunResult& r, const RomRunResult& ref) {
  double dr = 0, da = 0, rr = 0, ra = 0, path = 0;
  const std::size_t n = std::min(r.samples.size(), ref.samples.size());
  for (std::size_t i = 0; i < n; ++i) {
    const RomSample &a = r.samples[i], &b = ref.samples[i];
    dr += (a.yaw_rate - b.yaw_rate) * (a.yaw_rate - b.yaw_rate);
    da += (a.ay - b.ay) * (a.ay - b.ay);
    rr += b.yaw_rate * b.yaw_rate;
    ra += b.ay * b.ay;
    path = std::max(path, std::hypot(a.x - b.x, a.y - b.y));
  }
  return {std::sqrt(dr / rr), std::sqrt(da / ra), path};
}

}  // namespace

int main(int argc, char** argv) {
  const std::string out = argc > 1 ? argv[1] : "results/rom_accuracy_cost";
  std::filesystem::create_directories(out);
  const RomVehicle v = load_rom_vehicle("hmmwv");
  const std::vector<Case> cases = {
      {"iso3888_1 at 15 m/s", {{"type", "iso3888_1"}, {"initial_speed", 15}, {"target_speed", 15}}},
      {"step steer at 20 m/s",
       {{"type", "step_steer"}, {"steering", 0.15}, {"step_time", 1.0}, {"initial_speed", 20}, {"end_time", 5}}}};
  std::vector<Config> configs;
  for (RomModel m : {RomModel::k11Dof, RomModel::k18Dof, RomModel::k24Dof}) {
    for (double h : {4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4}) configs.push_back({m, RomIntegrator::kHalfImplicit, h});
    for (double tol : {1e-4, 1e-6, 1e-8}) configs.push_back({m, RomIntegrator::kCvodes, tol});
  }
  std::string csv =
      "case,model,integrator,step_or_rtol,wall_s,real_time_factor,rms_yaw_rate_rel,rms_ay_rel,max_path_m\n";
  std::string md =
      "| case | model | integrator | step / rtol | wall [ms] | × real time | yaw rate RMS err | ay RMS err | "
      "max path dev [m] |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const Case& c : cases) {
    const RomRunResult ref = run_case(v, c, {RomModel::k24Dof, RomIntegrator::kCvodes, 1e-10});
    const double sim = ref.samples.back().time;
    for (const Config& k : configs) {
      std::vector<double> walls;
      RomRunResult r;
      try {
        for (int rep = 0; rep < 3; ++rep) {
          r = run_case(v, c, k);
          walls.push_back(r.wall_seconds);
        }
      } catch (const std::exception& e) {
        md += fmt::format("| {} | {} | {} | {:g} | — | — | failed: {} | | |\n", c.name, model_name(k.model),
                          integrator_name(k.integrator), k.knob, e.what());
        continue;
      }
      std::sort(walls.begin(), walls.end());
      const double wall = walls[1];
      const Errors e = errors(r, ref);
      csv += fmt::format("{},{},{},{:g},{:.6g},{:.6g},{:.4g},{:.4g},{:.4g}\n", c.name, model_name(k.model),
                         integrator_name(k.integrator), k.knob, wall, sim / wall, e.yaw_rate, e.ay, e.path);
      md += fmt::format("| {} | {} | {} | {:g} | {:.2f} | {:.0f} | {:.2e} | {:.2e} | {:.3f} |\n", c.name,
                        model_name(k.model), integrator_name(k.integrator), k.knob, 1e3 * wall, sim / wall, e.yaw_rate,
                        e.ay, e.path);
      std::fflush(stdout);
    }
  }
  write_text_atomically(out + "/accuracy_cost.csv", csv);
  write_text_atomically(out + "/table.md", md);
  std::fputs(md.c_str(), stdout);
  return 0;
}
