#pragma once
// The 18-DOF double-track model (after LFDM's 18-DOF model): chassis longitudinal, lateral, yaw and
// roll motion, four wheel spins, tread deflections per tire and the crank, on flat rigid ground.
// Loads are quasi-static (axle_loads, lateral_transfer); wheels cannot lift off. The right-hand
// side is written once for the CPU and the GPU. State layout: docs/rom.md.
#include <cmath>

#include "core/host_device.hpp"
#include "core/vehicle/driver_inputs.hpp"
#include "rom/driveline.hpp"
#include "rom/four_wheels.hpp"
#include "rom/loads.hpp"
#include "rom/rom_sample.hpp"
#include "rom/wheel_contact.hpp"

namespace terracal::rom {

struct Rom18 {
  static constexpr const char* kName = "18dof";
  static constexpr int kWheels = 4;  // FL, FR, RL, RR
  enum : int {
    kX,
    kY,
    kYaw,
    kRoll,
    kVx,
    kVy,
    kYawRate,
    kRollRate,
    kSpin,
    kXe = kSpin + 4,
    kYe = kXe + 4,
    kCrank = kYe + 4
  };
  static constexpr int kStates = kCrank + 1;
  // Positions: the fixed-step scheme advances these with the velocities already stepped.
  static TERRACAL_HD double roll_of(const double* y) { return y[kRoll]; }
  static TERRACAL_HD bool is_position(int i) { return i <= kRoll; }

  static TERRACAL_HD void kinematics(const RomVehicle& v, const double* y, double* dy) {
    const double c = cos(y[kYaw]), s = sin(y[kYaw]);
    dy[kX] = y[kVx] * c - y[kVy] * s;
    dy[kY] = y[kVx] * s + y[kVy] * c;
    dy[kYaw] = y[kYawRate];
    dy[kRoll] = v.has(kEffectRoll) ? y[kRollRate] : 0.0;
  }

  // Tire forces on the chassis for given chassis accelerations (they set the loads), and the roll
  // they were worked out at. The tires' forces are built in place: assigned from a temporary, their
  // 35 doubles were copied in every right-hand side (about 4 % of a CPU run, perf).
  struct Forces {
    FourWheelForces tires;
    double roll = 0, roll_rate = 0;
  };
  template <class G = OneLanePerVehicle>
  static TERRACAL_HD Forces forces(const RomVehicle& v, double cd, double sd, const double* y, double ax, double ay,
                                   const G& g = G{}) {
    const AxleLoads axle = axle_loads(v, ax);
    const double roll = v.has(kEffectRoll) ? y[kRoll] : steady_roll(v, ay);
    const double roll_rate = v.has(kEffectRoll) ? y[kRollRate] : 0.0;
    double fz[4];
    for (int w = 0; w < 4; ++w) {
      const double transfer = lateral_transfer(v, w / 2, ay, roll, roll_rate);
      fz[w] = 0.5 * (w < 2 ? axle.front : axle.rear) + (w % 2 == 0 ? -transfer : transfer);
    }
    return {four_wheel_contacts<Rom18>(v, cd, sd, y, fz, g), roll, roll_rate};
  }

  // dy = f(y). `smooth_dry`: brake and rolling resistance as smooth torques (ODE solvers); else
  // left out and reported in aux->dry_torque for the fixed-step scheme to apply implicitly.
  // `positions` false leaves the position rates out (the fixed-step scheme takes them after the
  // velocities). `g`: the lanes that share the vehicle's wheels (rom/wheel_group.hpp).
  template <class G = OneLanePerVehicle>
  static TERRACAL_HD void rhs(const RomVehicle& v, const DriverInput& in, int gear, const double* y, double* dy,
                              RomAux* aux, bool smooth_dry, bool positions = true, const G& g = G{}) {
    const double delta = steer_angle(v, in);
    const double cd = cos(delta), sd = sin(delta);
    const double m = v.total_mass();
    const double drag = aero_drag(v, y[kVx]);
    // The loads depend on the accelerations the forces cause. With relaxed tires the tread springs
    // (state) give them without a loop; steady tires take one more pass from the first estimate.
    double ax = 0, ay = 0;
    if (v.has(kEffectTireRelaxation)) {
      const Planar a = tread_spring_acceleration<Rom18>(v, cd, sd, y);
      ax = a.x;
      ay = a.y;
    } else {
      const Forces first = forces(v, cd, sd, y, 0.0, 0.0, g);
      ax = first.tires.fx / m;
      ay = first.tires.fy / m;
    }
    const Forces f = forces(v, cd, sd, y, ax - drag / m, ay, g);
    ax = (f.tires.fx - drag) / m;
    ay = f.tires.fy / m;
    dy[kVx] = ax + y[kVy] * y[kYawRate];
    dy[kVy] = ay - y[kVx] * y[kYawRate];
    dy[kYawRate] = f.tires.mz / v.yaw_inertia;
    if (v.has(kEffectRoll)) {
      const double hs = roll_arm(v);
      const double k = v.roll_stiffness[0] + v.roll_stiffness[1], c = v.roll_damping[0] + v.roll_damping[1];
      dy[kRollRate] = (v.mass * hs * (ay * cos(f.roll) + v.gravity * sin(f.roll)) - k * f.roll - c * f.roll_rate) /
                      (v.roll_inertia + v.mass * hs * hs);
    } else {
      dy[kRollRate] = 0.0;
    }
    four_wheel_spins<Rom18>(v, in, gear, y, f.tires, dy, aux, smooth_dry);
    if (positions) kinematics(v, y, dy);
    aux->ax = ax;
    aux->ay = ay;
    for (int w = 0; w < 4; ++w) aux->fz[w] = f.tires.fz[w];
  }

  // A vehicle rolling straight at `speed` with tires at their static loads; returns the gear.
  static TERRACAL_HD int initial_state(const RomVehicle& v, double speed, double* y) {
    for (int i = 0; i < kStates; ++i) y[i] = 0.0;
    y[kVx] = speed;
    const AxleLoads axle = axle_loads(v, 0.0);
    double mean_spin = 0;
    int n = 0;
    for (int w = 0; w < 4; ++w) {
      const double fz = 0.5 * (w < 2 ? axle.front : axle.rear);
      y[kSpin + w] = speed / tmeasy_at_load(v.tire[w / 2], fz).rdyn;
      if (is_driven(v.powertrain.drive, w < 2)) mean_spin += y[kSpin + w], ++n;
    }
    return initial_gear(v, mean_spin / n, y + kCrank);
  }

  static TERRACAL_HD RomSample sample(const RomVehicle& v, double t, const double* y, const RomAux& aux, int gear) {
    RomSample s = planar_sample<Rom18>(t, y, aux, gear);
    s.roll = v.has(kEffectRoll) ? y[kRoll] : steady_roll(v, aux.ay);
    s.roll_rate = v.has(kEffectRoll) ? y[kRollRate] : 0.0;
    return s;
  }
};

}  // namespace terracal::rom
