#pragma once
// The wheel-on-soil table of `terracal wheel-table` (docs/formats.md, "Wheel table"): the SCM
// single-wheel rig's steady drawbar pull, torque, sinkage and lateral force over loads x slips x
// slip angles, in HDF5; read back, validated, for the ROMs' `deformable_terrain` effect.
#include <string>
#include <vector>

#include "rom/terrain_table.hpp"

namespace terracal::rom {

struct TerrainTable {
  std::vector<double> load, slip, angle;  // axes: [N] per wheel, slip, [rad]
  // Measured, [load][slip][angle]: drawbar pull [N], drive torque [N m], sinkage [m], lateral [N].
  std::vector<double> dbp, torque, sinkage, lateral;
  double radius = 0, width = 0;  // the wheel [m]
  std::string soil, wheel;       // where they came from (the SCM set and wheel files)
  double duration = 0;           // simulated seconds per rig run
  // Per unit load, what the models look up (rom/terrain_table.hpp); filled by finish_coefficients.
  std::vector<double> thrust, resistance, lateral_coef;

  std::size_t index(std::size_t l, std::size_t s, std::size_t a) const {
    return (l * slip.size() + s) * angle.size() + a;
  }
  TerrainTableView view() const;
};

// Thrust T / (r Fz), resistance (T / r - DP) / Fz and lateral Fy / Fz from the measured arrays.
void finish_coefficients(TerrainTable& t);
// Writes `path` atomically (HDF5, docs/formats.md).
void write_terrain_table(const std::string& path, const TerrainTable& t);
// Reads and validates a table: InputError naming the file, the dataset and what was expected.
TerrainTable read_terrain_table(const std::string& path);
// read_terrain_table, once per path for the life of the process: the views the vehicles hold point
// into it.
const TerrainTable& load_terrain_table(const std::string& path);

struct RomVehicle;
// Reads the table at `path` (once per process) and turns on `deformable_terrain` with it.
void attach_terrain_table(RomVehicle& v, const std::string& path);

}  // namespace terracal::rom
