#pragma once
// Synthetic bevameter curves from known SCM parameters: the recovery tests, the demo data set and
// the benchmarks all draw their data from here, through the same forward models the fit uses.
#include <string>
#include <vector>

#include "bayes/observations.hpp"
#include "bayes/scm_parameters.hpp"
#include "core/range.hpp"
#include "core/rng.hpp"

namespace terracal::bayes {

struct SyntheticDesign {
  std::vector<double> plate_radii{0.1, 0.2};                  // m
  double max_sinkage = 0.1;                                   // m
  int plate_points = 20;                                      // per plate, evenly spaced in (0, max_sinkage]
  double annulus_inner = 0.15, annulus_outer = 0.20;          // m
  std::vector<double> shear_pressures{2e3, 8e3, 14e3, 20e3};  // normal pressure W/A [Pa]
  double max_angle = 0.8;                                     // rad
  int shear_points = 30;                                      // per load, evenly spaced in (0, max_angle]
  double relative_noise = 0.02;                               // sd of multiplicative Gaussian noise: y = f (1 + sd eps)
  // Load/unload/reload cycles: at each of these sinkages [m] every plate is unloaded elastically
  // (F = pi r^2 Ke (z - z_p)) down to lift-off, reloaded up the same line, then loading goes on.
  // Empty: monotone loading only.
  std::vector<double> unload_at;
  double elastic_stiffness = 4e7;  // Ke [Pa/m] of the cycles
  int unload_points = 8;           // rows per unload branch (the last at lift-off, F = 0) and per reload branch
};

// The designs `terracal synthesize` takes (its options check against these). The noise is
// multiplicative, y = f (1 + sd eps) with eps ~ N(0, 1): a value turns negative (and the file is then
// refused by `calibrate`) when eps < -1/sd. At sd = 0.2 that is eps < -5, probability 2.9e-7 per
// value (the default design's 160 values: once in 20,000 files); at 0.25 it would be 3.2e-5 (once in
// 200 files), at 0.5 2.3 %. Noisier data need another noise model than this one.
struct SyntheticRanges {
  static constexpr Range kPlateRadius{0, 10, true, false, "m"};
  static constexpr Range kMaxSinkage{0, 10, true, false, "m"};
  static constexpr long long kMaxPoints = 100000;  // samples per curve (at least 1)
  static constexpr Range kAnnulusRadius{0, 10, false, false, "m"};
  static constexpr Range kPressure{0, 1e9, true, false, "Pa"};
  static constexpr Range kMaxAngle{0, 100, true, false, "rad"};
  static constexpr Range kRelativeNoise{0, 0.2};
};
// Throws InputError naming the option (`terracal synthesize`'s) of the first value outside its range.
void validate(const SyntheticDesign& design);

PlateData synthesize_plate(const ParamVector& truth, const SyntheticDesign& design, Rng& rng);
ShearData synthesize_shear(const ParamVector& truth, const SyntheticDesign& design, Rng& rng);

// CSV in the formats of docs/formats.md, written atomically (plate: with the phase column
// when some row is not `load`).
void write_plate_csv(const std::string& path, const PlateData& data);
void write_shear_csv(const std::string& path, const ShearData& data);

}  // namespace terracal::bayes
