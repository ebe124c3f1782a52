#pragma once
// The unloaded 1 m cube of soil on which the hourglass effects' tests set the lattice's checkerboard
// mode going (columns of particles moving up and down, alternating along x and y), and the helpers
// that start it and read it back.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <initializer_list>

#include "core/errors.hpp"
#include "highfi/crm/crm_checkpoint.hpp"
#include "highfi/crm/crm_solver.hpp"
#include "tests/highfi/crm/crm_test_scenes.hpp"

namespace terracal::test::lattice_mode {

constexpr double kD0 = 0.05;
constexpr int kCells = 20;  // 1 x 1 x 1 m of soil, 8000 particles

// No gravity (so no stress) and no effects: the caller adds the one under test.
inline nlohmann::json unloaded_bed() {
  nlohmann::json j = bed_scene_json(kD0, kCells, kCells, 0);
  j["soil"]["gravity"] = {0, 0, 0};
  j["effects"] = nlohmann::json::array();
  return j;
}

inline int lattice_index(double x) { return int(std::lround(x / kD0 - 0.5)); }
inline int parity(const Vec4<double>& p) { return (lattice_index(p.x) + lattice_index(p.y)) % 2 == 0 ? 1 : -1; }

// Particles at least `margin` from the walls, the floor and the free surface.
inline bool interior(const Vec4<double>& p, double margin) {
  const double size = kCells * kD0;
  return p.x > margin && p.x < size - margin && p.y > margin && p.y < size - margin && p.z > margin &&
         p.z < size - margin;
}

// Runs `steps` steps from the lattice with velocities v(position); returns the soil.
inline HostSoil run(const CrmScene& sc, const std::function<Vec3<double>(const Vec4<double>&)>& v, int steps) {
  HostSoil bed = initial_bed(sc);
  for (std::size_t i = 0; i < bed.size(); ++i) {
    const Vec3<double> u = v(bed.pos[i]);
    bed.vel[i] = {u.x, u.y, u.z, bed.vel[i].w};
  }
  CrmSolver s(sc, validation_device(), &bed);
  for (int k = 0; k < steps; ++k) s.step();
  return s.soil();
}

// The amplitude of the checkerboard mode (vertical velocity times parity) among particles at least
// `margin` inside.
inline double checkerboard_amplitude(const HostSoil& s, double margin) {
  double sum = 0;
  long n = 0;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (interior(s.pos[i], margin)) {
      sum += parity(s.pos[i]) * s.vel[i].z;
      ++n;
    }
  return sum / double(n);
}

// An opt-in effect E with one setting, as the hourglass effects' tests check it. bed(on, value) is
// the scene with the effect named (on) and its setting at value. Named, the effect is on with that
// setting; the setting is part of the cache key; each of `bad` is refused with an error that names
// `error_key`; a setting for an effect that is not named is refused.
template <class E>
void check_effect_setting(const std::function<nlohmann::json(bool, double)>& bed, double good, double other,
                          std::initializer_list<double> bad, const char* error_key) {
  const auto spec = E::settings()[0];
  const CrmScene off = scene_from(bed(false, good));
  const CrmScene on = scene_from(bed(true, good));
  CHECK(on.effects.on<E>());
  CHECK(spec.get(on.effects.of<E>()) == good);
  CHECK(crm_fingerprint(on, CrmDevice::kCpu, false) != crm_fingerprint(off, CrmDevice::kCpu, false));
  CrmScene changed = on;
  typename E::Settings s = on.effects.of<E>();
  spec.put(s, other);
  changed.effects.enable<E>(s);
  CHECK(crm_fingerprint(on, CrmDevice::kCpu, false) != crm_fingerprint(changed, CrmDevice::kCpu, false));
  for (double value : bad) {
    try {
      scene_from(bed(true, value));
      FAIL(E::kName << " setting " << value << " was accepted");
    } catch (const InputError& e) {
      CHECK_THAT(e.what(), Catch::Contains(error_key));
    }
  }
  nlohmann::json j = bed(false, good);
  j[E::kName] = bed(true, good)[E::kName];  // settings for an effect that is not named
  CHECK_THROWS_AS(scene_from(j), InputError);
}

}  // namespace terracal::test::lattice_mode
