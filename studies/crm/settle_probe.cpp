// How a CRM bed settles: a bed of depth H released from the lattice with the lithostatic stress
// (initial_bed, as settling starts), with the kinetic energy, the largest particle speed and the
// surface height of the middle of the bin printed every 0.025 s as CSV. Optionally the velocities
// are zeroed at t_zero (as settled_bed does at the end of --settle-time) and the run goes on, to
// show what a rig placed on that bed would meet. The surface is measured as a CrmSite measures it.
// Usage: crm_settle_probe DEPTH SPACING WIDTH T_END [T_ZERO=0] [cpu|cuda] [JITTER=0 (settle_jitter)]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "highfi/crm_scene.hpp"
#include "highfi/crm_solver.hpp"
#include "highfi/crm_terrain.hpp"

using namespace terracal;

int main(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr, "usage: %s DEPTH SPACING WIDTH T_END [T_ZERO=0] [cpu|cuda] [JITTER=0]\n", argv[0]);
    return 2;
  }
  const double depth = std::atof(argv[1]), d0 = std::atof(argv[2]), width = std::atof(argv[3]), t_end = std::atof(argv[4]);
  const double t_zero = argc > 5 ? std::atof(argv[5]) : 0;
  const CrmDevice device = argc > 6 && std::string(argv[6]) == "cuda" ? CrmDevice::kCuda : CrmDevice::kCpu;
  const double jitter = argc > 7 ? std::atof(argv[7]) : 0;
  CrmScene sc;  // CrmSoil's defaults are the bevameter study soil (2022) of shared/reference
  sc.bin.size = {width, width, 1.5 * depth};
  sc.bin.fill_height = depth;
  sc.numerics.spacing = d0;
  sc.effects.artificial_viscosity = true;  // as the rigs' sites
  sc.settle_jitter = jitter;               // 0: released from the exact lattice
  validate_crm_scene(sc);
  const HostSoil bed0 = settling_start(sc);
  auto solver = std::make_unique<CrmSolver>(sc, device, &bed0);
  const double dt = solver->time_step();
  const double mass = sc.soil.density * width * width * depth;
  std::printf("# bed %.3g m deep, %.3g x %.3g m, spacing %.3g m, jitter %.3g, %zu particles, step %.3g s; 4H/c = %.3g s\n", depth, width, width, d0, jitter,
              solver->soil().size(), dt, 4 * depth / sc.soil.sound_speed());
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
      std::printf("%.4f,%.5g,%.4g,%.4g,%.6f\n", k * dt, st.kinetic_energy, std::sqrt(2 * st.kinetic_energy / mass), st.max_speed,
                  bed_surface_height(solver->soil(), sc));
      std::fflush(stdout);
    }
  }
  return 0;
}
