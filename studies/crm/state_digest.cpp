// Runs a CRM scene for a number of steps and prints, as CSV, every body's wrench (17 digits) at
// chosen steps and, at the end, a digest of the whole particle state: two builds that print the
// same lines computed the same bits. Used to show that a change of the code's structure left the
// results bit-identical (studies/crm/bitcheck.sh, every combination of the CRM effects).
// Usage: crm_state_digest SCENE.json STEPS EVERY [cpu|cuda] [EFFECTS|-] [double|float]
//   EFFECTS: comma-separated effect names that replace the scene's list (settings of effects left
//   out are dropped); "-" or absent keeps the scene's own; "none" names none.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#if __has_include("highfi/crm/crm_solver.hpp")
#include "highfi/crm/crm_scene.hpp"
#include "highfi/crm/crm_solver.hpp"
#else
#include "highfi/crm_scene.hpp"
#include "highfi/crm_solver.hpp"
#endif
#include "core/checksum.hpp"
#include "core/json_file.hpp"

using namespace terracal;

namespace {

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> out;
  std::size_t at = 0;
  while (at <= text.size()) {
    const std::size_t end = std::min(text.find(',', at), text.size());
    if (end > at) out.push_back(text.substr(at, end - at));
    at = end + 1;
  }
  return out;
}

// FNV-1a over the bytes of the state as the engine returns it (doubles).
struct Digest {
  terracal::Fnv1a64 h;
  void add(const std::vector<Vec4<double>>& v) {
    for (const auto& r : v) {
      const double f[4] = {r.x, r.y, r.z, r.w};
      h.add(f, sizeof f);
    }
  }
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: %s SCENE.json STEPS EVERY [cpu|cuda] [EFFECTS|-] [double|float]\n", argv[0]);
    return 2;
  }
  nlohmann::json j = read_json_file(argv[1], "scene file");
  const long steps = std::atol(argv[2]), every = std::atol(argv[3]);
  const CrmDevice device = argc > 4 && std::string(argv[4]) == "cuda" ? CrmDevice::kCuda : CrmDevice::kCpu;
  if (argc > 5 && std::string(argv[5]) != "-") {
    const std::vector<std::string> named = std::string(argv[5]) == "none" ? std::vector<std::string>{} : split(argv[5]);
    for (const char* e :
         {"artificial_viscosity", "shifting", "active_domain", "hourglass_damping", "hourglass_stiffness"})
      if (std::find(named.begin(), named.end(), e) == named.end()) j.erase(e);
    if (std::find(named.begin(), named.end(), "cohesion") == named.end()) j["soil"]["cohesion"] = 0;
    j["effects"] = named;
  }
  if (argc > 6) j["resolution"]["cpu_precision"] = argv[6];
  const CrmScene sc = parse_crm_scene(j, argv[1]);
  CrmSolver s(sc, device);
  std::printf("step,body,fx,fy,fz,tx,ty,tz\n");
  for (long k = 1; k <= steps; ++k) {
    s.step();
    if (every > 0 && k % every == 0)
      for (std::size_t b = 0; b < s.wrenches().size(); ++b) {
        const BodyWrench& w = s.wrenches()[b];
        std::printf("%ld,%zu,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", k, b, w.force.x, w.force.y, w.force.z, w.torque.x,
                    w.torque.y, w.torque.z);
      }
  }
  const HostSoil soil = s.soil();
  Digest d;
  d.add(soil.pos);
  d.add(soil.vel);
  d.add(soil.s0);
  d.add(soil.s1);
  if (std::getenv("DIGEST_DUMP"))
    for (std::size_t i = 0; i < soil.size(); ++i)
      std::fprintf(stderr, "%zu %a %a %a %a | %a %a %a %a | %a %a %a %a | %a %a %a %a\n", i, soil.pos[i].x,
                   soil.pos[i].y, soil.pos[i].z, soil.pos[i].w, soil.vel[i].x, soil.vel[i].y, soil.vel[i].z,
                   soil.vel[i].w, soil.s0[i].x, soil.s0[i].y, soil.s0[i].z, soil.s0[i].w, soil.s1[i].x, soil.s1[i].y,
                   soil.s1[i].z, soil.s1[i].w);
  const SoilStats st = s.stats();
  std::printf("# particles %zu, lost %ld, frozen %ld, kinetic energy %.17g, state digest %016llx\n", soil.size(),
              st.lost, st.frozen, st.kinetic_energy, static_cast<unsigned long long>(d.h.value()));
  return 0;
}
