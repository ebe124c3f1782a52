// Validation 12: the backends agree. A plate pushed into a bed for 200 steps; positions compared
// by particle id. The CPU twin (float64 against float32 on the CPU) always runs; the CUDA half runs
// when a device is present and says that it skipped otherwise.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <string>

#include "highfi/crm/crm_solver.hpp"
#include "tests/highfi/crm/crm_test_scenes.hpp"
#include "tests/skip.hpp"

using namespace terracal;

namespace {

nlohmann::json plate_scene(const std::string& precision) {
  nlohmann::json j = test::bed_scene_json(0.01, 14, 8);
  j["resolution"]["cpu_precision"] = precision;
  j["effects"] = {"artificial_viscosity", "shifting", "hourglass_damping",
                  "hourglass_stiffness"};  // every effect's kernel path
  j["bodies"] = {{{"name", "plate"},
                  {"shape", {{"type", "disc"}, {"radius", 0.04}, {"thickness", 0.02}}},
                  {"position", {0.07, 0.07, 0.08 + 0.012}},
                  {"motion", {{"type", "prescribed"}, {"linear_velocity", {0, 0, -0.2}}}}}};
  return j;
}

HostSoil run(const CrmScene& sc, CrmDevice device, int steps, double* plate_force) {
  CrmSolver s(sc, device);
  for (int i = 0; i < steps; ++i) s.step();
  *plate_force = s.wrenches()[0].force.z;
  return s.soil();
}

// Relative L2 difference of positions, matched by particle id.
double relative_l2(const HostSoil& a, const HostSoil& b) {
  std::vector<Vec3<double>> pa(a.size()), pb(b.size());
  for (std::size_t i = 0; i < a.size(); ++i) pa[std::size_t(a.ids[i])] = a.pos[i].xyz();
  for (std::size_t i = 0; i < b.size(); ++i) pb[std::size_t(b.ids[i])] = b.pos[i].xyz();
  double num = 0, den = 0;
  for (std::size_t i = 0; i < pa.size(); ++i) {
    const Vec3<double> d = pa[i] - pb[i];
    num += dot(d, d);
    den += dot(pa[i], pa[i]);
  }
  return std::sqrt(num / den);
}

}  // namespace

TEST_CASE("CRM: float32 and float64 CPU runs agree over 200 steps", "[highfi][crm][device]") {
  double f64 = 0, f32 = 0;
  const HostSoil a = run(test::scene_from(plate_scene("double")), CrmDevice::kCpu, 200, &f64);
  const HostSoil b = run(test::scene_from(plate_scene("float")), CrmDevice::kCpu, 200, &f32);
  const double d = relative_l2(a, b);
  std::printf("CPU float64 vs float32: relative L2 of positions %.3e; plate force %.3f N vs %.3f N\n", d, f64, f32);
  CHECK(d < 1e-4);
  CHECK(f64 > 0);  // the plate is pushed into the soil: the soil pushes back up
  CHECK(f32 == Approx(f64).epsilon(0.02));
}

TEST_CASE("CRM: CUDA and CPU agree over 200 steps", "[highfi][crm][device][gpu]") {
  if (!test::cuda_device_or_skip("CRM: CUDA and CPU agree over 200 steps")) return;
  double fc = 0, fg = 0;
  const HostSoil a = run(test::scene_from(plate_scene("float")), CrmDevice::kCpu, 200, &fc);
  const HostSoil b = run(test::scene_from(plate_scene("float")), CrmDevice::kCuda, 200, &fg);
  const double d = relative_l2(a, b);
  std::printf("CPU float32 vs CUDA float32: relative L2 of positions %.3e; plate force %.3f N vs %.3f N\n", d, fc, fg);
  CHECK(d < 1e-4);
  CHECK(fg == Approx(fc).epsilon(0.02));
}
