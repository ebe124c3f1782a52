// How a CRM bed settles: a bed of depth H released from the lattice with the lithostatic stress
// (initial_bed, as settling starts), with the kinetic energy, the largest particle speed and the
// surface height of the middle of the bin printed every 0.025 s as CSV. Optionally the velocities
// are zeroed at t_zero (as settled_bed does at the end of --settle-time) and the run goes on, to
// show what a rig placed on that bed would meet. The surface is measured as a CrmSite measures it.
// Usage: crm_settle_probe DEPTH SPACING WIDTH T_END [T_ZERO=0] [cpu|cuda] [JITTER=0 (settle_jitter)] [EFFECTS]
// EFFECTS: a comma-separated list of effects besides artificial_viscosity: shifting, hourglass_damping[:ALPHA];
// h:H_OVER_D0 in the list sets the smoothing length instead (default 1.2).
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "highfi/crm/crm_scene.hpp"
#include "highfi/crm/crm_solver.hpp"
#include "highfi/crm/crm_terrain.hpp"

using namespace terracal;

namespace {
// The effects named in EXTRA besides artificial_viscosity; false (after a message) on an unknown one.
bool enable_effects(const std::string& extra, CrmScene& sc) {
  for (std::size_t at = 0; at < extra.size();) {
    std::size_t end = extra.find(',', at);
    if (end == std::string::npos) end = extra.size();
    const std::string item = extra.substr(at, end - at);
    at = end + 1;
    if (item == "shifting") {
      sc.effects.enable<Shifting>();
    } else if (item.rfind("hourglass_damping", 0) == 0) {
      HourglassDamping::Settings hg;
      if (item.size() > 18 && item[17] == ':') hg.alpha = std::atof(item.c_str() + 18);
      sc.effects.enable<HourglassDamping>(hg);
    } else if (item.rfind("h:", 0) == 0) {
      sc.numerics.h_over_d0 = std::atof(item.c_str() + 2);  // the smoothing length h/d0 (not an effect)
    } else {
      std::fprintf(stderr, "unknown effect '%s' (expected shifting, hourglass_damping[:ALPHA] or h:H_OVER_D0)\n",
                   item.c_str());
      return false;
    }
  }
  return true;
}

void print_layers(const HostSoil& end, double top, double width, double d0, const CrmScene& sc) {
  // What settling left near the surface, per layer of the middle of the bin (a comment block after
  // the CSV rows, top ten layers): mean density, accumulated plastic shear strain, and the friction
  // the stress mobilises, tau / (mu_s p) (1 = at yield; the lithostatic start is 0.76 at nu = 0.3).
  constexpr int kLayers = 10;
  std::vector<std::array<double, 4>> acc(kLayers, {0, 0, 0, 0});  // density, plastic strain, mobilised, count
  for (std::size_t i = 0; i < end.size(); ++i) {
    const auto& p = end.pos[i];
    if (std::abs(p.x - 0.5 * width) > 0.25 * width || std::abs(p.y - 0.5 * width) > 0.25 * width) continue;
    const int layer = int((top - p.z) / d0);
    if (layer < 0 || layer >= kLayers) continue;
    const auto &a0 = end.s0[i], &a1 = end.s1[i];
    const double pressure = -(a0.x + a0.y + a0.z) / 3;
    const double dx = a0.x + pressure, dy = a0.y + pressure, dz = a0.z + pressure;
    const double tau = std::sqrt(0.5 * (dx * dx + dy * dy + dz * dz) + a0.w * a0.w + a1.x * a1.x + a1.y * a1.y);
    auto& a = acc[std::size_t(layer)];
    a[0] += p.w, a[1] += a1.z, a[2] += pressure > 0 ? tau / (sc.soil.mu_s * pressure) : 1.0, a[3] += 1;
  }
  std::printf(
      "# by layer below the surface (%.4f m), middle of the bin: layer, density kg/m^3, plastic shear strain, "
      "tau/(mu_s p), particles\n",
      top);
  for (int l = 0; l < kLayers; ++l)
    if (const auto& a = acc[std::size_t(l)]; a[3] > 0)
      std::printf("# %d, %.2f, %.3g, %.3f, %d\n", l, a[0] / a[3], a[1] / a[3], a[2] / a[3], int(a[3]));
}

void print_top_roughness(const HostSoil& end, double top, double width, double d0) {
  // How rough the surface a rig meets is: the heights of the top layer's particles (middle of the
  // bin) about their mean; a lattice bed starts with all of them at one height.
  double sum = 0, sum2 = 0, lo = 1e30, hi = -1e30;
  long n = 0;
  for (std::size_t i = 0; i < end.size(); ++i) {
    const auto& p = end.pos[i];
    if (std::abs(p.x - 0.5 * width) > 0.25 * width || std::abs(p.y - 0.5 * width) > 0.25 * width) continue;
    if (p.z < top - d0) continue;  // within half a spacing of the top layer's mean height
    sum += p.z, sum2 += p.z * p.z, lo = std::min(lo, p.z), hi = std::max(hi, p.z), ++n;
  }
  const double mean = n ? sum / double(n) : 0;
  std::printf("# top layer heights (middle of the bin, %ld particles): rms %.3g m about the mean, range %.3g m\n", n,
              n ? std::sqrt(std::max(0.0, sum2 / double(n) - mean * mean)) : 0.0, hi - lo);
}

void print_velocity_correlation(const HostSoil& end, double d0) {
  // Is the motion smooth or does it alternate from one particle to the next? The correlation of the
  // velocities of neighbours one spacing apart along x, y and z, sum v_i . v_j / sum |v_i|^2 over
  // the particles near their lattice site: near +1 for a smooth (physical) motion, near -1 for a
  // checkerboard (a mode the SPH gradients do not see).
  std::map<std::array<long, 3>, std::size_t> site;
  auto lattice = [&](const Vec4<double>& p) {
    return std::array<long, 3>{std::lround(p.x / d0 - 0.5), std::lround(p.y / d0 - 0.5), std::lround(p.z / d0 - 0.5)};
  };
  for (std::size_t i = 0; i < end.size(); ++i) site[lattice(end.pos[i])] = i;
  for (int axis = 0; axis < 3; ++axis) {
    double vv = 0, v2 = 0;
    for (std::size_t i = 0; i < end.size(); ++i) {
      auto key = lattice(end.pos[i]);
      ++key[std::size_t(axis)];
      const auto it = site.find(key);
      if (it == site.end()) continue;
      const auto &a = end.vel[i], &b = end.vel[it->second];
      vv += a.x * b.x + a.y * b.y + a.z * b.z;
      v2 += a.x * a.x + a.y * a.y + a.z * a.z;
    }
    std::printf("# velocity correlation of neighbours along %c: %.3f\n", "xyz"[axis], v2 > 0 ? vv / v2 : 0.0);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr,
                 "usage: %s DEPTH SPACING WIDTH T_END [T_ZERO=0] [cpu|cuda] [JITTER=0] "
                 "[shifting,hourglass_damping[:ALPHA],h:H_OVER_D0]\n",
                 argv[0]);
    return 2;
  }
  const double depth = std::atof(argv[1]), d0 = std::atof(argv[2]), width = std::atof(argv[3]),
               t_end = std::atof(argv[4]);
  const double t_zero = argc > 5 ? std::atof(argv[5]) : 0;
  const CrmDevice device = argc > 6 && std::string(argv[6]) == "cuda" ? CrmDevice::kCuda : CrmDevice::kCpu;
  const double jitter = argc > 7 ? std::atof(argv[7]) : 0;
  const std::string extra = argc > 8 ? argv[8] : "";
  CrmScene sc;  // CrmSoil's defaults are the bevameter study soil (2022) of shared/reference
  sc.bin.size = {width, width, 1.5 * depth};
  sc.bin.fill_height = depth;
  sc.numerics.spacing = d0;
  sc.effects.enable<ArtificialViscosity>();  // as the rigs' sites
  if (!enable_effects(extra, sc)) return 2;
  sc.settle_jitter = jitter;  // 0: released from the exact lattice
  validate_crm_scene(sc);
  const HostSoil bed0 = settling_start(sc);
  auto solver = std::make_unique<CrmSolver>(sc, device, &bed0);
  const double dt = solver->time_step();
  const double mass = sc.soil.density * width * width * depth;
  std::printf(
      "# bed %.3g m deep, %.3g x %.3g m, spacing %.3g m, h/d0 %.3g, jitter %.3g, %zu particles, step %.3g s; 4H/c = "
      "%.3g s; effects: "
      "artificial_viscosity%s%s\n",
      depth, width, width, d0, sc.numerics.h_over_d0, jitter, solver->soil().size(), dt,
      4 * depth / sc.soil.sound_speed(), sc.effects.on<Shifting>() ? ", shifting" : "",
      sc.effects.on<HourglassDamping>()
          ? (", hourglass_damping " + std::to_string(sc.effects.of<HourglassDamping>().alpha)).c_str()
          : "");
  std::printf("t_s,kinetic_energy_J,rms_speed_m_s,max_speed_m_s,surface_m\n");
  const long every = std::max(1L, long(std::lround(0.025 / dt)));
  bool zeroed = !(t_zero > 0);
  for (long k = 1; k * dt <= t_end + 1e-12; ++k) {
    if (!zeroed && k * dt > t_zero) {
      HostSoil s = solver->soil();
      for (auto& v : s.vel) v = {0, 0, 0, v.w};
      solver = std::make_unique<CrmSolver>(sc, device, &s);
      zeroed = true;
      std::printf("# velocities zeroed at t = %.4g s\n", (k - 1) * dt);
    }
    solver->step();
    if (k % every == 0) {
      const SoilStats st = solver->stats();
      std::printf("%.4f,%.5g,%.4g,%.4g,%.6f\n", k * dt, st.kinetic_energy, std::sqrt(2 * st.kinetic_energy / mass),
                  st.max_speed, bed_surface_height(solver->soil(), sc));
      std::fflush(stdout);
    }
  }
  const HostSoil end = solver->soil();
  const double top = bed_surface_height(end, sc);
  print_layers(end, top, width, d0, sc);
  print_top_roughness(end, top, width, d0);
  print_velocity_correlation(end, d0);
  return 0;
}
