#pragma once
// What the four-wheel models (18 and 24 DOF) share: the wheel positions, the four tires' contact
// forces on the chassis for given loads, and the wheel spins, tread deflections and crank under the
// driveline, brakes and rolling resistance. Templated on the model for its state layout.
#include <cmath>

#include "core/host_device.hpp"
#include "core/vehicle/driver_inputs.hpp"
#include "rom/driveline.hpp"
#include "rom/wheel_contact.hpp"
#include "rom/wheel_group.hpp"

namespace terracal::rom {

// Wheel w (FL, FR, RL, RR) relative to the CG, chassis frame.
TERRACAL_HD_INLINE double wheel_x(const RomVehicle& v, int w) { return w < 2 ? v.cg_to_front : -v.cg_to_rear; }
TERRACAL_HD_INLINE double wheel_y(const RomVehicle& v, int w) { return (w % 2 == 0 ? 0.5 : -0.5) * v.track[w / 2]; }

struct FourWheelForces {
  double fx = 0, fy = 0, mz = 0;  // on the chassis, chassis frame [N], [N m]
  double fx_axle[2] = {}, fy_axle[2] = {};
  WheelContact w[4];
  double fz[4] = {};
};

// Wheel w's contact as the lane that computed it has it (one lane: its own slot w).
template <class G>
TERRACAL_HD_INLINE WheelContact contact_of_wheel(const G& g, const WheelContact (&mine)[G::kSlots], int w) {
  if constexpr (G::kLanes == 1) {
    return mine[w];
  } else {
    WheelContact c;
    c.fx = g.from_wheel(mine[0].fx, w);
    c.fy = g.from_wheel(mine[0].fy, w);
    c.dxe = g.from_wheel(mine[0].dxe, w);
    c.dye = g.from_wheel(mine[0].dye, w);
    c.rdyn = g.from_wheel(mine[0].rdyn, w);
    c.resist = g.from_wheel(mine[0].resist, w);
    return c;
  }
}

// The four tires in stages (loads, slips, stiffnesses, forces), each stage over all wheels: the
// wheels' long chains of divisions and square roots are independent, and laid side by side the CPU
// overlaps them (about 1.3x faster than wheel after wheel on the dev VM). The same functions as
// wheel_contact. With a group of four GPU lanes (rom/wheel_group.hpp) each lane's stages take its
// own wheel, and the contacts are exchanged before the chassis sums, which every lane adds in wheel
// order as one lane does.
template <class M, class G = OneLanePerVehicle>
TERRACAL_HD_INLINE FourWheelForces four_wheel_contacts(const RomVehicle& v, double cd, double sd, const double* y,
                                                       const double* fz, const G& g = G{}) {
  constexpr int kSlots = G::kSlots;
  TmeasyLoadState st[kSlots];
  Planar vw[kSlots];
  double load[kSlots];
  for (int j = 0; j < kSlots; ++j) {
    const int w = g.wheel(j), axle = w / 2;
    load[j] = G::of_wheel(fz, w);
    const double px = wheel_x(v, w), py = wheel_y(v, w);
    vw[j] = to_wheel_frame(y[M::kVx] - y[M::kYawRate] * py, y[M::kVy] + y[M::kYawRate] * px, axle == 0 ? cd : 1.0,
                           axle == 0 ? sd : 0.0);
    st[j] = tmeasy_at_load(v.tire[axle], load[j], v.friction);
  }
  TmeasySlips sl[kSlots];
  for (int j = 0; j < kSlots; ++j)
    sl[j] = tmeasy_slips(vw[j].x, vw[j].y, G::of_wheel(y + M::kSpin, g.wheel(j)), st[j].rdyn);
  TmeasyStiffness k[kSlots];
  for (int j = 0; j < kSlots; ++j) k[j] = tmeasy_steady_stiffness(st[j], sl[j].sx, sl[j].sy, load[j]);
  SoilContact soil[kSlots];
  for (int j = 0; j < kSlots; ++j) soil[j] = soil_contact(v, load[j], sl[j], vw[j].x, 1.0, &k[j]);
  WheelContact mine[kSlots];
  for (int j = 0; j < kSlots; ++j) {
    const int w = g.wheel(j);
    const TmeasyParams& tire = v.tire[w / 2];
    const double xe = G::of_wheel(y + M::kXe, w), ye = G::of_wheel(y + M::kYe, w);
    WheelContact& c = mine[j];
    c.rdyn = st[j].rdyn;
    if (load[j] <= 0.0) {  // a wheel off the ground: no force; the tread relaxes
      c.dxe = -xe * tire.longitudinal_stiffness / tire.longitudinal_damping;
      c.dye = -ye * tire.lateral_stiffness / tire.lateral_damping;
    } else if (v.has(kEffectTireRelaxation)) {
      const TmeasyRelaxed r =
          tmeasy_relaxed(tire, k[j], sl[j], vw[j].x, vw[j].y, G::of_wheel(y + M::kSpin, w), st[j].rdyn, xe, ye);
      c.fx = r.fx;
      c.fy = r.fy;
      c.dxe = r.dxe;
      c.dye = r.dye;
    } else {
      c.fx = k[j].kx * sl[j].sx;
      c.fy = k[j].ky * sl[j].sy;
    }
    c.fx += soil[j].thrust0;
    c.resist = soil[j].resist;
  }
  FourWheelForces f;
  for (int w = 0; w < 4; ++w) {
    const int axle = w / 2;
    f.fz[w] = fz[w];
    WheelContact& c = f.w[w];
    c = contact_of_wheel(g, mine, w);
    const Planar fc = to_chassis_frame(c.fx + c.resist, c.fy, axle == 0 ? cd : 1.0, axle == 0 ? sd : 0.0);
    f.fx += fc.x;
    f.fy += fc.y;
    f.fx_axle[axle] += fc.x;
    f.fy_axle[axle] += fc.y;
    f.mz += wheel_x(v, w) * fc.y - wheel_y(v, w) * fc.x;
  }
  return f;
}

// The chassis acceleration the tread springs alone give (a state: no algebraic loop), for the
// quasi-static load transfer of the relaxed tires.
template <class M>
TERRACAL_HD_INLINE Planar tread_spring_acceleration(const RomVehicle& v, double cd, double sd, const double* y) {
  Planar a;
  const double m = v.total_mass();
  for (int w = 0; w < 4; ++w) {
    const TmeasyParams& t = v.tire[w / 2];
    const Planar fc = to_chassis_frame(t.longitudinal_stiffness * y[M::kXe + w], t.lateral_stiffness * y[M::kYe + w],
                                       w < 2 ? cd : 1.0, w < 2 ? sd : 0.0);
    a.x += fc.x / m;
    a.y += fc.y / m;
  }
  return a;
}

// Spins, tread deflection rates and crank: dy for those states; aux gets the dry-friction bounds.
template <class M>
TERRACAL_HD_INLINE void four_wheel_spins(const RomVehicle& v, const DriverInput& in, int gear, const double* y,
                                         const FourWheelForces& f, double* dy, RomAux* aux, bool smooth_dry) {
  bool driven[4];
  double j[4], tau[4], mean_spin = 0;
  int n_driven = 0;
  for (int w = 0; w < 4; ++w) {
    driven[w] = is_driven(v.powertrain.drive, w < 2);
    if (driven[w]) mean_spin += y[M::kSpin + w], ++n_driven;
  }
  mean_spin /= n_driven;
  const Driveline d = driveline(v, gear, clamp_to(in.throttle, 0.0, 1.0), y[M::kCrank], mean_spin, n_driven);
  const double brake = clamp_to(in.braking, 0.0, 1.0) * v.powertrain.max_brake_torque;
  for (int w = 0; w < 4; ++w) {
    const TmeasyParams& t = v.tire[w / 2];
    j[w] = t.wheel_inertia;
    tau[w] = (driven[w] ? d.wheel_torque : 0.0) - f.w[w].fx * f.w[w].rdyn;
    double dry = brake;
    if (v.has(kEffectRollingResistance)) dry += t.rolling_resistance * max_of(f.fz[w], 0.0) * f.w[w].rdyn;
    if (smooth_dry) tau[w] += dry_friction_torque(dry, y[M::kSpin + w]);
    aux->dry_torque[w] = smooth_dry ? 0.0 : dry;
    aux->spin_inertia[w] = j[w] + (driven[w] ? d.coupling * n_driven : 0.0);
    dy[M::kXe + w] = v.has(kEffectTireRelaxation) ? f.w[w].dxe : 0.0;
    dy[M::kYe + w] = v.has(kEffectTireRelaxation) ? f.w[w].dye : 0.0;
  }
  spin_accelerations(4, driven, j, d.coupling, tau, dy + M::kSpin);
  dy[M::kCrank] = d.crank_accel;
  aux->engine_speed = d.engine_speed;
  aux->gearbox_input_speed = d.input_speed;
}

}  // namespace terracal::rom
