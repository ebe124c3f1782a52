// The hourglass_damping effect (results/crm_settling): a Laplacian viscosity between soil particles
// that damps the lattice's checkerboard mode (columns moving up and down, alternating along x and
// y), which the velocity gradient does not see and which grows under the lithostatic stress.
// - without the effect the mode is a zero-energy mode: it keeps its amplitude;
// - with it, it decays at the rate the SPH Laplacian predicts on the lattice,
//   Lambda = 4 nu d0^3 sum over neighbours of the other parity of |W'/r| r^2/(r^2 + 0.01 h^2);
// - a linear velocity field (uniform shear plus a rigid rotation) is left alone in the interior;
// - the key is validated, and named in the cache key only when on.
// Gravity is off so that the bed has no stress: only the effect acts on the mode.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "core/errors.hpp"
#include "highfi/crm/crm_checkpoint.hpp"
#include "highfi/crm/crm_solver.hpp"
#include "highfi/crm/sph_kernel.hpp"
#include "tests/highfi/crm/crm_lattice_mode.hpp"
#include "tests/highfi/crm/crm_test_scenes.hpp"

using namespace terracal;

using namespace terracal::test::lattice_mode;

namespace {

nlohmann::json unloaded_bed(bool hourglass, double alpha) {
  nlohmann::json j = test::lattice_mode::unloaded_bed();
  if (hourglass) {
    j["effects"].push_back("hourglass_damping");
    j["hourglass_damping"] = {{"alpha", alpha}};
  }
  return j;
}

}  // namespace

TEST_CASE("CRM: hourglass_damping damps the checkerboard mode at the rate of the SPH Laplacian", "[highfi][crm]") {
  constexpr double kAmplitude = 1e-3, kAlpha = 0.2;
  const CrmScene off = test::scene_from(unloaded_bed(false, kAlpha));
  const CrmScene on = test::scene_from(unloaded_bed(true, kAlpha));
  const double h = on.numerics.smoothing_length(), dt = on.numerics.time_step;
  const int steps = 25;
  const double t = steps * dt;

  // The predicted rate: nu = alpha h c / 10, and the lattice sum over neighbours of the other parity.
  const double nu = kAlpha * h * on.soil.sound_speed() / 10;
  const SphKernel<double> kernel = SphKernel<double>::make(on.numerics.kernel, h);
  double sum = 0;
  for (int a = -3; a <= 3; ++a)
    for (int b = -3; b <= 3; ++b)
      for (int c = -3; c <= 3; ++c) {
        if ((a + b) % 2 == 0) continue;
        const double r2 = kD0 * kD0 * (a * a + b * b + c * c), r = std::sqrt(r2);
        if (r >= 2 * h) continue;
        sum += -kernel.values(r).f * r2 / (r2 + 0.01 * h * h);
      }
  const double rate = 4 * nu * kD0 * kD0 * kD0 * sum;

  auto mode = [&](const Vec4<double>& p) { return Vec3<double>{0, 0, kAmplitude * parity(p)}; };
  const double margin = 4 * h;  // away from the walls' and the surface's influence
  const double kept = checkerboard_amplitude(run(off, mode, steps), margin) / kAmplitude;
  const double damped = checkerboard_amplitude(run(on, mode, steps), margin) / kAmplitude;
  const double expected = std::exp(-rate * t);
  std::printf(
      "checkerboard mode after %.4g s: %.4f of its amplitude without the effect, %.4f with (predicted %.4f, "
      "rate %.1f 1/s)\n",
      t, kept, damped, expected, rate);
  CHECK(kept == Approx(1).margin(0.02));
  CHECK(expected < 0.7);  // the check below is not trivially met
  CHECK(damped == Approx(expected).epsilon(0.03));
}

TEST_CASE("CRM: hourglass_damping leaves a linear velocity field alone", "[highfi][crm]") {
  // Uniform shear dv_x/dz plus a rigid rotation about z: the interior moves exactly as without the
  // effect (one step reaches 2 supports into the bin: the margin keeps the walls' influence out).
  const CrmScene off = test::scene_from(unloaded_bed(false, 0.2));
  const CrmScene on = test::scene_from(unloaded_bed(true, 0.2));
  const double h = on.numerics.smoothing_length();
  auto linear = [](const Vec4<double>& p) {
    const double shear = 0.01, spin = 0.02;
    return Vec3<double>{shear * p.z - spin * (p.y - 0.5), spin * (p.x - 0.5), 0};
  };
  const HostSoil a = run(off, linear, 1), b = run(on, linear, 1);
  // The same step on the checkerboard, for scale.
  auto mode = [](const Vec4<double>& p) { return Vec3<double>{0, 0, 0.01 * parity(p)}; };
  const HostSoil c = run(off, mode, 1), d = run(on, mode, 1);
  const double margin = 5 * h;
  double linear_change = 0, mode_change = 0, speed = 0;
  long n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    REQUIRE(a.ids[i] == b.ids[i]);
    if (!interior(a.pos[i], margin)) continue;
    ++n;
    const Vec3<double> dv = a.vel[i].xyz() - b.vel[i].xyz();
    linear_change = std::max(linear_change, std::sqrt(dot(dv, dv)));
    speed = std::max(speed, std::sqrt(dot(a.vel[i].xyz(), a.vel[i].xyz())));
  }
  for (std::size_t i = 0; i < c.size(); ++i)
    if (interior(c.pos[i], margin)) mode_change = std::max(mode_change, std::abs(c.vel[i].z - d.vel[i].z));
  std::printf(
      "one step, %ld interior particles: the effect changes a linear field (speeds up to %.3g m/s) by %.3g m/s, "
      "the checkerboard (0.01 m/s) by %.3g m/s\n",
      n, speed, linear_change, mode_change);
  REQUIRE(n > 100);
  // A damping that did not vanish on linear fields would change them by about as much as the mode.
  CHECK(mode_change > 1e-4);
  CHECK(linear_change < 1e-4 * mode_change);
}

TEST_CASE("CRM: hourglass_damping is validated and keyed", "[highfi][crm]") {
  test::lattice_mode::check_effect_setting<HourglassDamping>([](bool on, double v) { return unloaded_bed(on, v); }, 0.2,
                                                             0.3, {0.0, -1.0, 3.0}, "alpha");
}
