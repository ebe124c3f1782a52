#include "lowfi/scm_wheels.hpp"

#include <fmt/format.h>

#include "core/errors.hpp"

namespace terracal::lowfi {

namespace {
void check(const ScmWheelShape& w, const char* key, double v, double lo, double hi, const char* unit) {
  if (!(v >= lo && v <= hi))
    throw InputError(fmt::format("SCM wheel '{}': {} = {}: expected in [{}, {}] {}", w.name, key, v, lo, hi, unit));
}

// The wheels as terrain bodies: shapes only, every degree of freedom driven from outside, placed a
// metre above the soil so that the terrain's first contact pass finds nothing.
std::vector<RigidBody> wheel_bodies(const ScmSettings& settings, const std::vector<ScmWheelShape>& wheels) {
  std::vector<RigidBody> bodies;
  for (const ScmWheelShape& w : wheels) {
    validate(w);
    RigidBody b;
    b.name = w.name;
    b.shape = wheel_shape(w.radius, w.width, w.grouser_count, w.grouser_height, w.grouser_thickness);
    b.position = {0, 0, settings.surface_height + b.bounding_radius() + 1.0};
    bodies.push_back(std::move(b));
  }
  return bodies;
}
}  // namespace

void validate(const ScmWheelShape& w) {
  check(w, "radius", w.radius, 0.01, 10, "m");
  check(w, "width", w.width, 0.005, 10, "m");
  check(w, "grouser_count", w.grouser_count, 0, 360, "");
  check(w, "grouser_height", w.grouser_height, 0, 0.5 * w.radius, "m (at most half the radius)");
  check(w, "grouser_thickness", w.grouser_thickness, 0, w.radius, "m");
  if (w.grouser_count > 0 && !(w.grouser_height > 0 && w.grouser_thickness > 0))
    throw InputError(
        fmt::format("SCM wheel '{}': grouser_count = {} needs grouser_height > 0 and "
                    "grouser_thickness > 0 (got {}, {})",
                    w.name, w.grouser_count, w.grouser_height, w.grouser_thickness));
}

ScmWheels::ScmWheels(const ScmSoil& soil, const ScmSettings& settings, const std::vector<ScmWheelShape>& wheels)
    : shapes_(wheels), terrain_(soil, settings, wheel_bodies(settings, wheels)) {}

void ScmWheels::step(const std::vector<BodyState>& wheels) { terrain_.step_at(wheels); }

}  // namespace terracal::lowfi
