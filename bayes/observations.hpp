#pragma once
// Bevameter observations as read from the curve files of DESIGN.md section 3, validated once.
// A loaded data set is immutable and every number in it is in SI units.
#include <string>
#include <vector>

namespace terracal::bayes {

enum class PlatePhase { kLoad, kUnload, kReload };

struct PlatePoint {
  double radius = 0, sinkage = 0, force = 0;
  PlatePhase phase = PlatePhase::kLoad;
  int line = 0;            // line in the file, for messages
  bool fitted = false;     // used by the Bekker fit: loading beyond the previous maximum sinkage, z > 0
};

struct PlateData {
  std::string path;
  std::vector<PlatePoint> points;
  std::vector<double> radii;   // the distinct plate radii, ascending
  int fitted_count() const;
};

struct ShearPoint {
  double inner_radius = 0, outer_radius = 0, normal_load = 0, torque = 0;
  double angle = 0;
  bool developed = false;  // no angle given: the fully developed torque
  int line = 0;
};

struct ShearData {
  std::string path;
  std::vector<ShearPoint> points;
};

// Load and validate. Bad input throws InputError naming the file, line, column, value and what was
// expected: missing columns, non-numeric or non-finite cells, negative or zero radii, negative
// sinkage, sinkage or radii that look like millimetres, an unknown phase, an unload row deeper than
// its plate's deepest sinkage so far, an empty file.
PlateData load_plate_csv(const std::string& path);
ShearData load_shear_csv(const std::string& path);

}  // namespace terracal::bayes
