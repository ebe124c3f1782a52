#include "highfi/vehicle/rigid_ground_tire.hpp"

#include <cmath>

namespace terracal::vehicle {

using mb::Vec3;

TireContact RigidGroundTire::apply(const mb::RigidBody& spindle, mb::Wrench& w) const {
  TireContact c;
  const Vec3 axis = spindle.rotation() * Vec3::UnitY();
  const Vec3 up = Vec3::UnitZ();
  // The wheel's heading (forward) and the direction from its centre down to the ground in its plane.
  const Vec3 heading_raw = axis.cross(up);
  if (heading_raw.norm() < 1e-6) return c;  // the wheel lies flat: no rolling contact
  const Vec3 heading = heading_raw.normalized(), lateral = up.cross(heading);
  const Vec3 down = axis.cross(heading).normalized();  // in the wheel plane, pointing at the ground
  if (down.z() > -1e-6) return c;
  const double reach = spindle.position.z() / -down.z();  // from the centre to the ground along `down`
  c.deflection = params.unloaded_radius - reach;
  if (c.deflection <= 0) return c;
  c.touching = true;
  c.point = spindle.position + reach * down;
  const Vec3 v = spindle.velocity;
  const double omega = (spindle.rotation() * spindle.omega).dot(axis);
  // The deflection's rate: the centre's sinking (not its sliding: `down` leans sideways when the
  // wheel is cambered), seen along `down` as the reach is.
  const double rate = v.z() / down.z();
  // The damping fades in over the first millimetres of deflection, so that the force is continuous
  // when a wheel touches down or lifts off (a step there stalls the integrator), and never pulls.
  const double fade = std::min(1.0, c.deflection / kDampingFadeDeflection);
  c.fz = std::max(0.0, params.vertical_stiffness * c.deflection + fade * vertical_damping * rate);
  const TmeasyLoadState st = tmeasy_at_load(params, c.fz, friction);
  const double vx = v.dot(heading), vy = v.dot(lateral);
  const TmeasySlips s = tmeasy_slips(vx, vy, omega, st.rdyn);
  const TmeasyStiffness k = tmeasy_steady_stiffness(st, s.sx, s.sy, c.fz);
  c.sx = s.sx;
  c.sy = s.sy;
  c.fx = k.kx * s.sx;
  c.fy = k.ky * s.sy;
  mb::add_force_at(spindle, spindle.rotation().transpose() * (c.point - spindle.position),
                   c.fx * heading + c.fy * lateral + c.fz * up, w);
  // Rolling resistance against the spin.
  const double resistance = -params.rolling_resistance * c.fz * st.rdyn * std::tanh(omega / 0.1);
  w.torque += spindle.rotation().transpose() * (resistance * axis);
  return c;
}

}  // namespace terracal::vehicle
