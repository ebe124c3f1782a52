#pragma once
// Annulus-shear rig: an annulus under a dead normal load (free to sink), left to
// settle, then turned at a constant rate; torque against angle for each load (the rows of
// shear.csv, docs/formats.md). Gives the Mohr-Coulomb c, phi and the Janosi k.
#include <string>
#include <vector>

#include "core/terrain.hpp"
#include "virtual_bevameter/rig_progress.hpp"

namespace terracal::rigs {

struct ShearTest {
  double inner_radius = 0.15, outer_radius = 0.20;  // [m]
  std::vector<double> loads;                        // normal loads [N]; each a separate run on a fresh terrain
  double angular_velocity = 1.0;                    // [rad/s]
  double max_angle = 1.0;                           // [rad] turned after settling
  double settle_time = 1.0;  // [s] under the load before turning (the bounce of the drop must die out)
  double load_ramp = 0;      // [s] the load grows from zero over this part of the settling; 0: dropped at once
  double thickness = 0.02;   // [m]
  int samples = 100;         // rows per load over the turn
};
void validate(const ShearTest& test);

struct ShearRow {
  double inner_radius = 0, outer_radius = 0, normal_load = 0, angle = 0, torque = 0;
  double sinkage = 0;  // of the annulus's underside below the undisturbed surface
};

// Torque is what the drive applies (minus the soil's torque about the vertical axis).
std::vector<ShearRow> run_shear(const TerrainSite& site, const ShearTest& test, const RigProgress& progress = {});

// shear.csv (inner_radius_m,outer_radius_m,normal_load_N,angle_rad,torque_Nm; docs/formats.md), plus the
// annulus's sinkage (sinkage_m; the calibrator ignores it), atomically.
void write_shear_csv(const std::string& path, const std::vector<ShearRow>& rows);

}  // namespace terracal::rigs
