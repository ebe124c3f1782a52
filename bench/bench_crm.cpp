// CRM particle-steps per second (soil particles x full steps / wall second),
// device memory per particle, and the speed-up of active_domain for a single wheel in a 4 m bin.
// Each figure is the median of `repeats` timed blocks of `steps` steps after a warm-up.
// Usage: bench_crm cpu|cuda [particles=1e5,...] [steps=20] [repeats=5] [wheel[=d0]]
//   A bed of about N particles fills a square bin to a depth of 1/4 of its side (full domain). Two
//   lines per size: `rigs`, the configuration the rigs run (h/d0 1.4, Wendland C2, the effects
//   artificial_viscosity, hourglass_damping 0.4 and hourglass_stiffness 0.03, and a plate's markers
//   pressing into the bed), and `bare`, the kernel alone (h/d0 1.2, artificial_viscosity, no body).
//   `wheel`: a wheel crossing a 4 m x 1 m bin, full domain vs active_domain, at d0 = 0.02 m (150 000
//   particles) or the spacing given; with the wheel's mean force over the timed steps. Particles 0
//   leaves out the bed lines; BENCH_WHEEL=off or on times that wheel alone (for profiles).
//   TERRACAL_CRM_SORT_ALL=1 sorts every marker at every pose (the order the long way), for comparisons;
//   BENCH_SORT_SKIN=s sets resolution.sort_skin (0: the soil sorted at every step). `sorted %`: the
//   timed steps that sorted the soil; `plate_fz_N`: the plate's mean vertical force over the timed steps
//   (a check that builds compared for speed agree).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/bench_stats.hpp"
#include "highfi/crm/crm_solver.hpp"

using namespace terracal;
using Clock = std::chrono::steady_clock;

using bench::median;

static nlohmann::json soil() {
  return {{"density", 1700},
          {"young_modulus", 1e6},
          {"poisson_ratio", 0.3},
          {"mu_s", 0.7},
          {"mu_2", 0.7},
          {"I0", 0.03},
          {"grain_diameter", 0.005},
          {"cohesion", 0},
          {"gravity", {0, 0, -9.81}}};
}

struct Timing {
  double rate;  // particle-steps per second
  std::size_t particles, markers, bytes;
  std::string device;
  Vec3<double> force;  // the first body's mean force over the timed steps
  double sorted;       // the fraction of the timed steps that sorted the soil (resolution.sort_skin)
};

// BENCH_SORT_SKIN=s times resolution.sort_skin s instead of the default (0: sort at every step).
static void apply_bench_settings(nlohmann::json& j) {
  if (const char* skin = std::getenv("BENCH_SORT_SKIN")) j["resolution"]["sort_skin"] = std::atof(skin);
}

static Timing time_scene(nlohmann::json j, CrmDevice device, int steps, int repeats) {
  apply_bench_settings(j);
  CrmScene sc = parse_crm_scene(j, "bench scene");
  CrmSolver s(sc, device);
  for (int i = 0; i < 3; ++i) s.step();
  const long sorts_before = s.engine().sort_counts().soil;
  std::vector<double> rates;
  Vec3<double> force{};
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = Clock::now();
    for (int i = 0; i < steps; ++i) {
      s.step();
      if (!s.wrenches().empty()) force += (1.0 / (steps * repeats)) * s.wrenches()[0].force;
    }
    (void)s.stats();  // synchronises the device
    const double sec = std::chrono::duration<double>(Clock::now() - t0).count();
    rates.push_back(double(s.engine().soil_count()) * steps / sec);
  }
  const SoilStats st = s.stats();
  if (st.nonfinite > 0) std::fprintf(stderr, "warning: %ld non-finite particles\n", st.nonfinite);
  const double sorted = double(s.engine().sort_counts().soil - sorts_before) / double(steps * repeats);
  return {median(rates), s.engine().soil_count(), s.engine().marker_count(), s.engine().device_bytes(),
          s.engine().description(), force, sorted};
}

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_crm cpu|cuda [particles=1e5,...] [steps=20] [repeats=5] [wheel[=d0]]\n");
    return 2;
  }
  const CrmDevice device = std::string(argv[1]) == "cuda" ? CrmDevice::kCuda : CrmDevice::kCpu;
  std::vector<double> sizes;
  {
    std::stringstream ss(argc > 2 ? argv[2] : "1e5");
    std::string tok;
    while (std::getline(ss, tok, ',')) sizes.push_back(std::stod(tok));
  }
  const int steps = argc > 3 ? std::atoi(argv[3]) : 20;
  const int repeats = argc > 4 ? std::atoi(argv[4]) : 5;
  const std::string wheel_arg = argc > 5 ? argv[5] : "";
  const bool wheel = wheel_arg.rfind("wheel", 0) == 0;
  const double dw = wheel_arg.rfind("wheel=", 0) == 0 ? std::stod(wheel_arg.substr(6)) : 0.02;
  if (wheel && !(dw >= 0.005 && dw <= 0.1)) {
    std::fprintf(stderr, "bench_crm: wheel spacing %g m outside [0.005, 0.1]\n", dw);
    return 2;
  }
  const double d0 = 0.01;
  std::printf("%-6s %-12s %-12s %-10s %-16s %-14s %-8s %-12s %s\n", "config", "particles", "markers", "bytes/p",
              "particle-steps/s", "ms/step", "sorted%", "plate_fz_N", "device");
  for (double n : sizes)
    for (bool rigs : {true, false}) {
      if (!(n > 0)) continue;  // particles 0: the wheel alone
      // Square bin of side L filled to L/4: n = (L/d0)^2 (L/4d0).
      const int side = std::max(8, int(std::lround(std::cbrt(4 * n))));
      const int depth = std::max(4, side / 4);
      nlohmann::json j = {{"soil", soil()},
                          {"bin", {{"size", {side * d0, side * d0, (depth + 4) * d0}}, {"fill_height", depth * d0}}},
                          {"resolution", {{"spacing", d0}, {"h_over_d0", rigs ? 1.4 : 1.2}, {"cpu_precision", "float"}}},
                          {"effects", {"artificial_viscosity"}}};
      if (rigs) {
        j["effects"] = {"artificial_viscosity", "hourglass_damping", "hourglass_stiffness"};
        j["hourglass_damping"] = {{"alpha", 0.4}};
        j["hourglass_stiffness"] = {{"beta", 0.03}};
        // A plate (a sixth of the bin's side) pressing into the middle of the bed at 0.1 m/s, as the rig's.
        const double radius = side * d0 / 6, thickness = 2 * d0;
        j["bodies"] = {{{"name", "plate"},
                        {"shape", {{"type", "disc"}, {"radius", radius}, {"thickness", thickness}}},
                        {"position", {side * d0 / 2, side * d0 / 2, depth * d0 + thickness / 2}},
                        {"motion", {{"type", "prescribed"}, {"linear_velocity", {0, 0, -0.1}}}}}};
      }
      // BENCH_GRID_REACH=1 times the plain 2h grid instead of the default cells of h.
      if (const char* reach = std::getenv("BENCH_GRID_REACH")) j["resolution"]["grid_reach"] = std::atoi(reach);
      const Timing t = time_scene(j, device, steps, repeats);
      std::printf("%-6s %-12zu %-12zu %-10.1f %-16.4g %-14.3f %-8.0f %-12.6g %s\n", rigs ? "rigs" : "bare",
                  t.particles, t.markers, double(t.bytes) / t.particles, t.rate, 1e3 * t.particles / t.rate,
                  100 * t.sorted, t.force.z, t.device.c_str());
      std::fflush(stdout);
    }
  if (wheel) {
    // A wheel (radius 0.25 m, width 0.15 m) crossing a 4 m x 1 m bin 0.3 m deep.
    // BENCH_WHEEL=off or on times that one alone (for profiles).
    const char* only = std::getenv("BENCH_WHEEL");
    for (bool active : {false, true}) {
      if (only && std::string(only) != (active ? "on" : "off")) continue;
      nlohmann::json j = {
          {"soil", soil()},
          {"bin", {{"size", {4.0, 1.0, 0.4}}, {"fill_height", 0.3}}},
          {"resolution", {{"spacing", dw}, {"h_over_d0", 1.2}, {"cpu_precision", "float"}}},
          {"effects",
           active ? nlohmann::json{"artificial_viscosity", "active_domain"} : nlohmann::json{"artificial_viscosity"}},
          {"bodies",
           {{{"name", "wheel"},
             {"shape", {{"type", "cylinder"}, {"radius", 0.25}, {"width", 0.15}}},
             {"position", {0.5, 0.5, 0.3 + 0.25 - 0.02}},
             {"motion",
              {{"type", "prescribed"}, {"linear_velocity", {0.5, 0, 0}}, {"angular_velocity", {0, 2.0, 0}}}}}}}};
      if (active) j["active_domain"] = {{"margin", 0.1}};
      const Timing t = time_scene(j, device, steps, repeats);
      std::printf(
          "wheel bin 4 m, d0 %.3f, active_domain %-3s: %zu particles, %.4g particle-steps/s (%.3f ms/step); wheel "
          "force (%.2f, %.2f) N; soil sorted at %.0f %% of the steps\n",
          dw, active ? "on" : "off", t.particles, t.rate, 1e3 * t.particles / t.rate, t.force.x, t.force.z,
          100 * t.sorted);
    }
  }
  return 0;
}
