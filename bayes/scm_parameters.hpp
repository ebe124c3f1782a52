#pragma once
// The Bekker-Wong-Janosi parameters that the calibrator infers, in Chrono's SCM units:
// Kc [Pa/m^(n-1)], Kphi [Pa/m^n], n [-], cohesion c [Pa], friction angle phi [deg], Janosi k [m];
// and Lyasko's slip-sinkage S [-] (the block "Slip sinkage", lowfi/slip_sinkage.hpp), which only
// single-wheel curves identify: without them it is fixed and left out of every output.
// Two more are nuisance parameters of the annulus, free only with `--annulus-law scaled` (bevameter
// and wheel curves together; calibration_problem.hpp): the set's shear strength over the annulus's,
// R [-], and the annulus's own Janosi k [m]. They are not part of the SCM set.
#include <array>
#include <string_view>

namespace terracal::bayes {

enum Param : int {
  kKc = 0,
  kKphi,
  kN,
  kCohesion,
  kFriction,
  kJanosi,
  kSlipSinkage,
  kShearRatio,
  kAnnulusJanosi,
  kNumParams
};

// Names exactly as in Chrono's SCM JSON "Soil parameters" block (docs/formats.md).
inline constexpr std::array<std::string_view, kNumParams> kChronoNames = {
    "Bekker Kc",           "Bekker Kphi",         "Bekker n exponent",
    "Mohr cohesive limit", "Mohr friction limit", "Janosi shear coefficient", "Slip sinkage S",
    "Shear strength over annulus", "Annulus Janosi shear coefficient"};

// Short names: priors files, the posterior file and the summary table.
inline constexpr std::array<std::string_view, kNumParams> kShortNames = {"Kc", "Kphi", "n", "c", "phi",
                                                                         "k",  "S",    "R", "k_annulus"};
inline constexpr std::array<std::string_view, kNumParams> kUnits = {"Pa/m^(n-1)", "Pa/m^n", "1", "Pa", "deg",
                                                                    "m",          "1",      "1", "m"};

using ParamVector = std::array<double, kNumParams>;

}  // namespace terracal::bayes

namespace terracal::bayes {
// Index of a parameter by its short name ("Kphi") or Chrono name ("Bekker Kphi"); -1 if unknown.
int param_index(std::string_view short_or_chrono_name);
}  // namespace terracal::bayes
