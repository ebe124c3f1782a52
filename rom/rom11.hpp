#pragma once
// The 11-DOF single-track model (after LFDM's 11-DOF model): chassis longitudinal, lateral and yaw
// motion, one wheel spin and one tread deflection pair per axle (an axle's two tires lumped), and
// the crank. Loads: static plus longitudinal transfer. State layout: docs/rom.md.
#include <cmath>

#include "core/host_device.hpp"
#include "core/vehicle/driver_inputs.hpp"
#include "rom/driveline.hpp"
#include "rom/loads.hpp"
#include "rom/rom_sample.hpp"
#include "rom/wheel_contact.hpp"
#include "rom/wheel_group.hpp"

namespace terracal::rom {

struct Rom11 {
  static constexpr const char* kName = "11dof";
  static constexpr int kWheels = 2;  // front axle, rear axle
  enum : int { kX, kY, kYaw, kVx, kVy, kYawRate, kSpin, kXe = kSpin + 2, kYe = kXe + 2, kCrank = kYe + 2 };
  static constexpr int kStates = kCrank + 1;
  static TERRACAL_HD double roll_of(const double*) { return 0.0; }
  static TERRACAL_HD bool is_position(int i) { return i <= kYaw; }

  static TERRACAL_HD void kinematics(const RomVehicle&, const double* y, double* dy) {
    const double c = cos(y[kYaw]), s = sin(y[kYaw]);
    dy[kX] = y[kVx] * c - y[kVy] * s;
    dy[kY] = y[kVx] * s + y[kVy] * c;
    dy[kYaw] = y[kYawRate];
  }

  struct Forces {
    double fx = 0, fy = 0, mz = 0;
    WheelContact w[2];
    double fz[2] = {};
  };
  static TERRACAL_HD Forces forces(const RomVehicle& v, double cd, double sd, const double* y, double ax) {
    Forces f;
    const AxleLoads axle = axle_loads(v, ax);
    f.fz[0] = axle.front;
    f.fz[1] = axle.rear;
    for (int w = 0; w < 2; ++w) {
      const double px = w == 0 ? v.cg_to_front : -v.cg_to_rear;
      const double c = w == 0 ? cd : 1.0, s = w == 0 ? sd : 0.0;
      const Planar vw = to_wheel_frame(y[kVx], y[kVy] + y[kYawRate] * px, c, s);
      f.w[w] = wheel_contact(v, v.tire[w], f.fz[w], vw.x, vw.y, y[kSpin + w], y[kXe + w], y[kYe + w], 2.0);
      const Planar fc = to_chassis_frame(f.w[w].fx + f.w[w].resist, f.w[w].fy, c, s);
      f.fx += fc.x;
      f.fy += fc.y;
      f.mz += px * fc.y;
    }
    return f;
  }

  // The wheel group is taken for the batch's sake and must be one lane: two axles are not split.
  template <class G = OneLanePerVehicle>
  static TERRACAL_HD void rhs(const RomVehicle& v, const DriverInput& in, int gear, const double* y, double* dy,
                              RomAux* aux, bool smooth_dry, bool positions = true, const G& = G{}) {
    static_assert(G::kLanes == 1, "the single-track model runs one lane per vehicle");
    const double delta = steer_angle(v, in);
    const double cd = cos(delta), sd = sin(delta);
    const double m = v.total_mass();
    const double drag = aero_drag(v, y[kVx]);
    double ax = 0;  // for the load transfer, as in Rom18::rhs
    if (v.has(kEffectTireRelaxation)) {
      for (int w = 0; w < 2; ++w) {
        const TmeasyParams& t = v.tire[w];
        const double c = w == 0 ? cd : 1.0, s = w == 0 ? sd : 0.0;
        ax += 2.0 * (t.longitudinal_stiffness * y[kXe + w] * c - t.lateral_stiffness * y[kYe + w] * s) / m;
      }
    } else {
      ax = forces(v, cd, sd, y, 0.0).fx / m;
    }
    const Forces f = forces(v, cd, sd, y, ax - drag / m);
    ax = (f.fx - drag) / m;
    const double ay = f.fy / m;
    dy[kVx] = ax + y[kVy] * y[kYawRate];
    dy[kVy] = ay - y[kVx] * y[kYawRate];
    dy[kYawRate] = f.mz / v.yaw_inertia;
    bool driven[2];
    double j[2], tau[2], mean_spin = 0;
    int n_driven = 0;
    for (int w = 0; w < 2; ++w) {
      driven[w] = is_driven(v.powertrain.drive, w == 0);
      if (driven[w]) mean_spin += y[kSpin + w], ++n_driven;
    }
    mean_spin /= n_driven;
    // An axle is two wheels: its share of the drive torque and its inertia are doubled.
    const Driveline d = driveline(v, gear, clamp_to(in.throttle, 0.0, 1.0), y[kCrank], mean_spin, n_driven);
    const double brake = 2.0 * clamp_to(in.braking, 0.0, 1.0) * v.powertrain.max_brake_torque;
    for (int w = 0; w < 2; ++w) {
      const TmeasyParams& t = v.tire[w];
      j[w] = 2.0 * t.wheel_inertia;
      tau[w] = (driven[w] ? d.wheel_torque : 0.0) - f.w[w].fx * f.w[w].rdyn;
      double dry = brake;
      if (v.has(kEffectRollingResistance)) dry += t.rolling_resistance * max_of(f.fz[w], 0.0) * f.w[w].rdyn;
      if (smooth_dry) tau[w] += dry_friction_torque(dry, y[kSpin + w]);
      aux->dry_torque[w] = smooth_dry ? 0.0 : dry;
      aux->spin_inertia[w] = j[w] + (driven[w] ? d.coupling * n_driven : 0.0);
      aux->fz[w] = f.fz[w];
      dy[kXe + w] = v.has(kEffectTireRelaxation) ? f.w[w].dxe : 0.0;
      dy[kYe + w] = v.has(kEffectTireRelaxation) ? f.w[w].dye : 0.0;
    }
    spin_accelerations(2, driven, j, d.coupling, tau, dy + kSpin);
    dy[kCrank] = d.crank_accel;
    if (positions) kinematics(v, y, dy);
    aux->ax = ax;
    aux->ay = ay;
    aux->engine_speed = d.engine_speed;
    aux->gearbox_input_speed = d.input_speed;
  }

  static TERRACAL_HD int initial_state(const RomVehicle& v, double speed, double* y) {
    for (int i = 0; i < kStates; ++i) y[i] = 0.0;
    y[kVx] = speed;
    const AxleLoads axle = axle_loads(v, 0.0);
    double mean_spin = 0;
    int n = 0;
    for (int w = 0; w < 2; ++w) {
      y[kSpin + w] = speed / tmeasy_at_load(v.tire[w], 0.5 * (w == 0 ? axle.front : axle.rear)).rdyn;
      if (is_driven(v.powertrain.drive, w == 0)) mean_spin += y[kSpin + w], ++n;
    }
    return initial_gear(v, mean_spin / n, y + kCrank);
  }

  static TERRACAL_HD RomSample sample(const RomVehicle&, double t, const double* y, const RomAux& aux, int gear) {
    RomSample s = planar_sample<Rom11>(t, y, aux, gear);
    return s;
  }
};

}  // namespace terracal::rom
