#pragma once
// Plate-sinkage rig: a circular plate pushed into the soil at constant speed to a
// maximum sinkage, with one unload-reload cycle on the way; force against sinkage, with the phase
// of each sample (the rows of plate.csv, docs/formats.md). The loading part gives Bekker's Kc, Kphi, n;
// the unloading slope gives SCM's elastic stiffness.
#include <string>
#include <vector>

#include "core/terrain.hpp"
#include "virtual_bevameter/rig_progress.hpp"

namespace terracal::rigs {

struct PlateTest {
  double radius = 0.2;        // [m]; the Bekker width b of a circular plate
  double max_sinkage = 0.1;   // [m]
  double speed = 0.05;        // [m/s] down and up
  // [m/s] of the unload and of the reload back to where the unload began (0: `speed`). Slower than
  // the bed's elastic waves cross it, the unload slope is the bed's static stiffness.
  double unload_speed = 0;
  double unload_at = 0.6;     // the unload starts at this fraction of max_sinkage (0: no cycle)
  double unload_depth = 0.1;  // and lifts the plate by this fraction of the sinkage reached
  double thickness = 0.02;    // plate thickness [m] (for the CRM markers)
  int samples = 200;          // rows over the whole stroke
};
// Throws InputError naming the field, its value and the allowed range.
void validate(const PlateTest& test);

struct PlateRow {
  double radius = 0, sinkage = 0, force = 0;
  std::string phase;  // load, unload, reload
};

// Runs one plate on a fresh terrain of the site. Sinkage is measured from the undisturbed surface
// to the plate's underside; force is the soil's vertical force on the plate.
std::vector<PlateRow> run_plate(const TerrainSite& site, const PlateTest& test, const RigProgress& progress = {});

// plate.csv (plate_radius_m,sinkage_m,force_N,phase; docs/formats.md, "plate.csv"), written atomically.
void write_plate_csv(const std::string& path, const std::vector<PlateRow>& rows);

}  // namespace terracal::rigs
