#pragma once
// The parameters of a reduced-order vehicle, shared by the 11-, 18- and 24-DOF models: a plain
// struct (it is copied to the GPU per vehicle). Read and validated from JSON by rom_vehicle_json.
// Frame: ISO 8855 (x forward, y left, z up). SI units, radians.
#include "core/host_device.hpp"
#include "core/vehicle/powertrain.hpp"
#include "core/vehicle/tmeasy.hpp"
#include "rom/terrain_table.hpp"

namespace terracal::rom {

// The optional effects a vehicle file names ("effects": [...]); an effect not named costs nothing.
enum RomEffect : unsigned {
  kEffectTireRelaxation = 1u << 0,     // tread deflection states; else steady (non-relaxed) TMeasy forces
  kEffectTorqueConverter = 1u << 1,    // crank speed as a state behind a torque converter; else a locked crank
  kEffectRoll = 1u << 2,               // roll as a state (18/24 DOF); else the steady roll angle
  kEffectSuspension = 1u << 3,         // vertical travel per corner (24 DOF)
  kEffectAeroDrag = 1u << 4,           // 0.5 rho CdA v|v| against the motion
  kEffectRollingResistance = 1u << 5,  // rr Fz rdyn against each wheel's spin
  kEffectDeformableTerrain = 1u << 6,  // tire forces from a wheel-on-soil table (rom/terrain_table.hpp)
};
inline constexpr const char* kRomEffectNames[] = {"tire_relaxation",    "torque_converter", "roll",
                                                  "suspension",         "aero_drag",        "rolling_resistance",
                                                  "deformable_terrain"};
inline constexpr int kRomEffectCount = 7;

struct RomVehicle {
  // Chassis (sprung mass) and axles.
  double mass = 0;                    // sprung mass [kg]
  double unsprung_mass[2] = {};       // per axle, front and rear [kg]
  double cg_to_front = 0;             // a [m]
  double cg_to_rear = 0;              // b [m]
  double cg_height = 0;               // h of the sprung mass above ground [m]
  double yaw_inertia = 0;             // Jz [kg m^2]
  double roll_inertia = 0;            // Jx of the sprung mass about its CG [kg m^2]
  double pitch_inertia = 0;           // Jy of the sprung mass about its CG [kg m^2] (24 DOF)
  double track[2] = {};               // front, rear [m]
  double roll_center_height[2] = {};  // front, rear [m]
  double roll_stiffness[2] = {};      // front, rear [N m/rad]
  double roll_damping[2] = {};        // front, rear [N m s/rad]
  double max_steer = 0;               // road-wheel angle at steering = 1 [rad]
  // Suspension per corner (24 DOF): a spring and a damper between the body corner and the wheel,
  // preloaded to carry the static corner load with the body at cg_height.
  double spring_rate[2] = {};  // front, rear [N/m]
  double damper_rate[2] = {};  // front, rear [N s/m]
  // Tires (front, rear), powertrain, resistance, environment.
  TmeasyParams tire[2];
  PowertrainParams powertrain;
  double drag_area = 0;      // Cd A [m^2]
  double air_density = 1.2;  // [kg/m^3]
  double gravity = 9.81;     // [m/s^2], downwards
  double friction = 1.0;     // road friction relative to the tire data's (scales fm and fs)
  unsigned effects = 0;      // RomEffect bits
  // deformable_terrain: the table the tires take their forces from (attach_terrain_table); its
  // pointers are host memory, replaced by device copies in a GPU batch.
  TerrainTableView terrain;

  TERRACAL_HD double wheelbase() const { return cg_to_front + cg_to_rear; }
  TERRACAL_HD double total_mass() const { return mass + unsprung_mass[0] + unsprung_mass[1]; }
  TERRACAL_HD bool has(RomEffect e) const { return (effects & e) != 0; }
};

// What a model reports beside the state derivative: the chassis accelerations and the engine speed
// (trajectory.csv), and the dry-friction torque bounds the fixed-step scheme applies implicitly.
struct RomAux {
  double ax = 0, ay = 0;           // chassis-frame accelerations of the CG [m/s^2]
  double engine_speed = 0;         // crank [rad/s]
  double gearbox_input_speed = 0;  // turbine, or the crank without a converter [rad/s]
  double dry_torque[4] = {};       // brake + rolling resistance bound per wheel [N m]
  double spin_inertia[4] = {};     // the inertia that bound acts on [kg m^2]
  double fz[4] = {};               // vertical tire loads [N]
};

}  // namespace terracal::rom
