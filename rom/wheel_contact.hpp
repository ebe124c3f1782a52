#pragma once
// One tire on rigid ground, as every reduced-order model uses it: TMeasy forces in the wheel frame
// from the contact point's velocity, the spin and the load, relaxed (tread deflection states) or
// steady, scaled to `count` identical tires (2 for an axle of the single-track model).
#include <cmath>

#include "core/host_device.hpp"
#include "core/vehicle/driver_inputs.hpp"
#include "core/vehicle/tmeasy.hpp"
#include "rom/rom_vehicle.hpp"

namespace terracal::rom {

struct WheelContact {
  double fx = 0, fy = 0;    // force on the wheel at the contact, wheel frame [N]
  double dxe = 0, dye = 0;  // tread deflection rates (relaxed form) [m/s]
  double rdyn = 0;          // dynamic rolling radius [m]
  // deformable_terrain: the soil's resistance on the chassis (along the wheel, not on its spin) [N];
  // fx then includes the table's thrust, which alone turns the wheel.
  double resist = 0;
};

// deformable_terrain: the table's slip stiffnesses in place of TMeasy's (k), for `count` identical
// tires under fz_one each at contact speed vx (rom/terrain_table.hpp).
TERRACAL_HD_INLINE SoilContact soil_contact(const RomVehicle& v, double fz_one, const TmeasySlips& s, double vx,
                                            double count, TmeasyStiffness* k) {
  SoilContact c;
  if (!v.has(kEffectDeformableTerrain) || fz_one <= 0.0) return c;
  c = soil_stiffness(v.terrain, fz_one, s.sx, s.sy, vx, &k->kx, &k->ky);
  c.thrust0 *= count;
  c.resist *= count;
  return c;
}

TERRACAL_HD_INLINE WheelContact wheel_contact(const RomVehicle& v, const TmeasyParams& tire, double fz, double vx,
                                              double vy, double omega, double xe, double ye, double count) {
  WheelContact w;
  const double fz_one = fz / count;
  const TmeasyLoadState st = tmeasy_at_load(tire, fz_one, v.friction);
  w.rdyn = st.rdyn;
  if (fz_one <= 0.0) {  // a wheel off the ground: no force; the tread relaxes
    w.dxe = -xe * tire.longitudinal_stiffness / tire.longitudinal_damping;
    w.dye = -ye * tire.lateral_stiffness / tire.lateral_damping;
    return w;
  }
  const TmeasySlips s = tmeasy_slips(vx, vy, omega, st.rdyn);
  TmeasyStiffness k = tmeasy_steady_stiffness(st, s.sx, s.sy, fz_one);
  const SoilContact soil = soil_contact(v, fz_one, s, vx, count, &k);
  w.resist = soil.resist;
  if (v.has(kEffectTireRelaxation)) {
    const TmeasyRelaxed r = tmeasy_relaxed(tire, k, s, vx, vy, omega, st.rdyn, xe, ye);
    w.fx = count * r.fx;
    w.fy = count * r.fy;
    w.dxe = r.dxe;
    w.dye = r.dye;
  } else {
    w.fx = count * k.kx * s.sx;
    w.fy = count * k.ky * s.sy;
  }
  w.fx += soil.thrust0;
  return w;
}

// The road-wheel angle of the front wheels for a steering input (-1..1 of the maximum).
TERRACAL_HD_INLINE double steer_angle(const RomVehicle& v, const DriverInput& in) {
  return clamp_to(in.steering, -1.0, 1.0) * v.max_steer;
}

// The `aero_drag` effect: 0.5 rho CdA vx|vx| against the forward motion [N]; nothing when off.
TERRACAL_HD_INLINE double aero_drag(const RomVehicle& v, double vx) {
  return v.has(kEffectAeroDrag) ? 0.5 * v.air_density * v.drag_area * vx * fabs(vx) : 0.0;
}

// Velocity of a chassis point (px, py) in the chassis frame, turned into a wheel frame steered by
// delta; and a wheel-frame force turned back into the chassis frame.
struct Planar {
  double x = 0, y = 0;
};
TERRACAL_HD_INLINE Planar to_wheel_frame(double vx, double vy, double cos_d, double sin_d) {
  return {vx * cos_d + vy * sin_d, -vx * sin_d + vy * cos_d};
}
TERRACAL_HD_INLINE Planar to_chassis_frame(double fx, double fy, double cos_d, double sin_d) {
  return {fx * cos_d - fy * sin_d, fx * sin_d + fy * cos_d};
}

}  // namespace terracal::rom
