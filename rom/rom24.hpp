#pragma once
// The 24-DOF model (after LFDM's 24-DOF model): the body with six degrees of freedom (planar
// motion, heave, roll, pitch), each wheel with vertical travel on a spring and damper and a tire
// spring below it (a wheel leaves the ground when that spring is unloaded), four wheel spins, tread
// deflections and the crank. Horizontal tire forces act on the body at the roll-centre height
// (lateral) and at the ground (longitudinal); the body's small roll and pitch angles carry the
// corners. State layout: docs/rom.md.
#include <cmath>

#include "core/host_device.hpp"
#include "core/vehicle/driver_inputs.hpp"
#include "rom/four_wheels.hpp"
#include "rom/loads.hpp"
#include "rom/rom_sample.hpp"

namespace terracal::rom {

struct Rom24 {
  static constexpr const char* kName = "24dof";
  static constexpr int kWheels = 4;  // FL, FR, RL, RR
  enum : int {
    kX,
    kY,
    kZ,
    kYaw,
    kRoll,
    kPitch,  // body CG position (ground frame) and angles
    kVx,
    kVy,
    kVz,
    kYawRate,
    kRollRate,
    kPitchRate,
    kWheelZ,
    kWheelVz = kWheelZ + 4,  // wheel centre heights above ground, their rates
    kSpin = kWheelVz + 4,
    kXe = kSpin + 4,
    kYe = kXe + 4,
    kCrank = kYe + 4
  };
  static constexpr int kStates = kCrank + 1;
  static TERRACAL_HD double roll_of(const double* y) { return y[kRoll]; }
  static TERRACAL_HD bool is_position(int i) { return i <= kPitch || (i >= kWheelZ && i < kWheelVz); }

  // Static state: each tire and corner spring carries its share of the weight. As in the other
  // models, a and b locate the whole vehicle's CG (the body's reference point); the sprung mass's
  // own CG then sits sprung_cg_x ahead of it, the unsprung masses being at the axles.
  struct Statics {
    double corner_load[4];  // sprung weight on each corner spring [N]
    double wheel_z[4];      // wheel centre heights [m]
    double sprung_cg_x;     // [m]
  };
  static TERRACAL_HD Statics statics(const RomVehicle& v) {
    Statics s;
    const double l = v.wheelbase(), g = v.gravity, m = v.total_mass();
    s.sprung_cg_x = (v.cg_to_rear * v.unsprung_mass[1] - v.cg_to_front * v.unsprung_mass[0]) / v.mass;
    for (int w = 0; w < 4; ++w) {
      const int a = w / 2;
      const double axle_load = m * g * (a == 0 ? v.cg_to_rear : v.cg_to_front) / l;
      s.corner_load[w] = 0.5 * (axle_load - v.unsprung_mass[a] * g);
      const double tire_load = 0.5 * axle_load;
      s.wheel_z[w] = v.tire[a].unloaded_radius - tire_load / v.tire[a].vertical_stiffness;
    }
    return s;
  }

  static TERRACAL_HD void kinematics(const RomVehicle&, const double* y, double* dy) {
    const double c = cos(y[kYaw]), s = sin(y[kYaw]);
    dy[kX] = y[kVx] * c - y[kVy] * s;
    dy[kY] = y[kVx] * s + y[kVy] * c;
    dy[kZ] = y[kVz];
    dy[kYaw] = y[kYawRate];
    dy[kRoll] = y[kRollRate];
    dy[kPitch] = y[kPitchRate];
    for (int w = 0; w < 4; ++w) dy[kWheelZ + w] = y[kWheelVz + w];
  }

  // `g`: the lanes that share the vehicle's wheels (rom/wheel_group.hpp).
  template <class G = OneLanePerVehicle>
  static TERRACAL_HD void rhs(const RomVehicle& v, const DriverInput& in, int gear, const double* y, double* dy,
                              RomAux* aux, bool smooth_dry, bool positions = true, const G& g = G{}) {
    const double delta = steer_angle(v, in);
    const double cd = cos(delta), sd = sin(delta);
    const Statics st = statics(v);
    const double sr = sin(y[kRoll]), sp = sin(y[kPitch]);
    double fz[4], spring[4];
    for (int w = 0; w < 4; ++w) {
      const int a = w / 2;
      const double px = wheel_x(v, w), py = wheel_y(v, w);
      // Compression of the corner against the static configuration, and its rate.
      const double body = (y[kZ] - v.cg_height) + py * sr - px * sp;
      const double body_rate = y[kVz] + py * y[kRollRate] - px * y[kPitchRate];
      const double compression = (y[kWheelZ + w] - st.wheel_z[w]) - body;
      const double rate = y[kWheelVz + w] - body_rate;
      spring[w] = st.corner_load[w] + v.spring_rate[a] * compression + v.damper_rate[a] * rate;
      fz[w] = max_of(0.0, v.tire[a].vertical_stiffness * (v.tire[a].unloaded_radius - y[kWheelZ + w]));
    }
    const FourWheelForces f = four_wheel_contacts<Rom24>(v, cd, sd, y, fz, g);
    const double m = v.total_mass();
    const double drag = aero_drag(v, y[kVx]);
    const double ax = (f.fx - drag) / m, ay = f.fy / m;
    dy[kVx] = ax + y[kVy] * y[kYawRate];
    dy[kVy] = ay - y[kVx] * y[kYawRate];
    dy[kYawRate] = f.mz / v.yaw_inertia;
    double heave = -v.mass * v.gravity, roll = 0, pitch = 0;
    for (int w = 0; w < 4; ++w) {
      heave += spring[w];
      roll += wheel_y(v, w) * spring[w];
      pitch -= wheel_x(v, w) * spring[w];
      const int a = w / 2;
      const double mu = 0.5 * v.unsprung_mass[a];
      dy[kWheelVz + w] = (fz[w] - spring[w]) / mu - v.gravity;
    }
    // Horizontal forces reach the body at the roll centres (lateral) and the ground (longitudinal);
    // the weight's moment follows the tilt about those axes.
    for (int a = 0; a < 2; ++a) roll += (v.cg_height - v.roll_center_height[a]) * f.fy_axle[a];
    roll += v.mass * v.gravity * roll_arm(v) * sr;
    pitch += -v.cg_height * (f.fx - drag) + v.mass * v.gravity * (v.cg_height * sp + st.sprung_cg_x);
    dy[kVz] = heave / v.mass;
    dy[kRollRate] = roll / v.roll_inertia;
    dy[kPitchRate] = pitch / v.pitch_inertia;
    four_wheel_spins<Rom24>(v, in, gear, y, f, dy, aux, smooth_dry);
    if (positions) kinematics(v, y, dy);
    aux->ax = ax;
    aux->ay = ay;
    for (int w = 0; w < 4; ++w) aux->fz[w] = fz[w];
  }

  static TERRACAL_HD int initial_state(const RomVehicle& v, double speed, double* y) {
    for (int i = 0; i < kStates; ++i) y[i] = 0.0;
    const Statics st = statics(v);
    y[kVx] = speed;
    y[kZ] = v.cg_height;
    double mean_spin = 0;
    int n = 0;
    for (int w = 0; w < 4; ++w) {
      y[kWheelZ + w] = st.wheel_z[w];
      const double fz = v.tire[w / 2].vertical_stiffness * (v.tire[w / 2].unloaded_radius - st.wheel_z[w]);
      y[kSpin + w] = speed / tmeasy_at_load(v.tire[w / 2], fz).rdyn;
      if (is_driven(v.powertrain.drive, w < 2)) mean_spin += y[kSpin + w], ++n;
    }
    return initial_gear(v, mean_spin / n, y + kCrank);
  }

  static TERRACAL_HD RomSample sample(const RomVehicle&, double t, const double* y, const RomAux& aux, int gear) {
    RomSample s = planar_sample<Rom24>(t, y, aux, gear);
    s.z = y[kZ];
    s.roll = y[kRoll];
    s.pitch = y[kPitch];
    s.roll_rate = y[kRollRate];
    return s;
  }
};

}  // namespace terracal::rom
