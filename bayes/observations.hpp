#pragma once
// Bevameter observations (docs/formats.md, "plate.csv" and "shear.csv"), validated once.
// A loaded data set is immutable and every number in it is in SI units.
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace terracal::bayes {

enum class PlatePhase { kLoad, kUnload, kReload };

struct PlatePoint {
  double radius = 0, sinkage = 0, force = 0;
  PlatePhase phase = PlatePhase::kLoad;
  int line = 0;         // line in the file, for messages
  bool fitted = false;  // used by the Bekker fit: loading beyond the previous maximum sinkage, z > 0
};

struct PlateData {
  std::string path;
  std::vector<PlatePoint> points;
  std::vector<double> radii;       // the distinct plate radii, ascending
  std::vector<std::string> notes;  // rows kept out of the fit and why, for the user
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
  std::vector<std::string> notes;  // rows kept out of the data set and why, for the user
};

// Where point i's value of a column came from, for messages ("plate.csv:12, column 'force_N' (3)").
using PointLocator = std::function<std::string(std::size_t point, const std::string& column)>;

// Validate points from any source (a file, or a rig's curves in memory) into a data set. Bad input
// throws InputError naming the place (`where`), value and what was expected: negative or zero radii,
// negative sinkage, sinkage or radii that look like millimetres, no loading rows, and a plate whose
// rows are not in the order of its test (a loading row shallower than an earlier row of its plate, an
// unload row deeper than the one before it or than the deepest sinkage so far, a reload that follows
// no unload). Plates may be interleaved: the data set holds each plate's rows together, in their
// order. Every row is kept; those the Bekker fit cannot use (sinkage 0) are counted in `notes`.
// `source` names the data set as a whole.
PlateData make_plate_data(std::vector<PlatePoint> points, const std::string& source, const PointLocator& where);
// Shear points at angle 0 (not developed) carry no information (the torque model is 0 there): they
// are left out of the data set and counted in `notes`; every bad point throws.
ShearData make_shear_data(std::vector<ShearPoint> points, const std::string& source, const PointLocator& where);

// Read a curve file and validate it as above; besides, missing columns, non-numeric or non-finite
// cells, an unknown phase and an empty file are refused.
PlateData load_plate_csv(const std::string& path);
ShearData load_shear_csv(const std::string& path);

// A phase as the curve files spell it: "load" (or empty), "unload", "reload"; nullopt otherwise.
std::optional<PlatePhase> parse_plate_phase(const std::string& text);

}  // namespace terracal::bayes
