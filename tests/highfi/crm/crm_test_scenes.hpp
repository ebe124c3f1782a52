#pragma once
// Small CRM scenes for the CPU twins of the validation tests (and the GPU runs of the same scenes).
#include <cstdio>
#include <cstdlib>
#include <string>

#include <nlohmann/json.hpp>

#include "highfi/crm/crm_scene.hpp"

namespace terracal::test {

// A bin of `cells` x `cells` spacings filled `layers` deep with the bevameter study soil.
inline nlohmann::json bed_scene_json(double d0, int cells, int layers, double settle = 0.1) {
  return {{"soil",
           {{"density", 1700},
            {"young_modulus", 1e6},
            {"poisson_ratio", 0.3},
            {"mu_s", 0.7},
            {"mu_2", 0.7},
            {"I0", 0.03},
            {"grain_diameter", 0.005},
            {"cohesion", 0},
            {"gravity", {0, 0, -9.81}}}},
          {"bin", {{"size", {cells * d0, cells * d0, (layers + 4) * d0}}, {"fill_height", layers * d0}}},
          {"resolution", {{"spacing", d0}, {"h_over_d0", 1.2}}},
          {"effects", {"artificial_viscosity"}},
          {"settle_time", settle}};
}

// A small bed (6 x 6 spacings of 0.01 m, 4 deep, not settled) with a disc pressed into it, 0.003 s long:
// the command-line tests' scene.
inline nlohmann::json plate_scene_json() {
  nlohmann::json j = bed_scene_json(0.01, 6, 4, 0.0);
  j["duration"] = 0.003;
  j["bodies"] = {{{"name", "plate"},
                  {"shape", {{"type", "disc"}, {"radius", 0.02}, {"thickness", 0.01}}},
                  {"position", {0.03, 0.03, 0.05}},
                  {"motion", {{"type", "prescribed"}, {"linear_velocity", {0, 0, -0.1}}}}}};
  return j;
}

// The device the validation scenes (lithostatic bed, coupling, slope, hard cases) run on: the CPU,
// as in CI, or the GPU when TERRACAL_TEST_DEVICE=cuda, which is how the device machine runs the
// same tests on the same scenes. Asking for cuda where there is none fails the tests loudly.
inline CrmDevice validation_device() {
  const char* d = std::getenv("TERRACAL_TEST_DEVICE");
  const bool cuda = d != nullptr && std::string(d) == "cuda";
  static bool said = false;
  if (!said) {
    std::printf("validation scenes on the %s (TERRACAL_TEST_DEVICE=%s)\n", cuda ? "GPU" : "CPU", d ? d : "");
    said = true;
  }
  return cuda ? CrmDevice::kCuda : CrmDevice::kCpu;
}

inline CrmScene scene_from(const nlohmann::json& j) { return parse_crm_scene(j, "test scene"); }

}  // namespace terracal::test
