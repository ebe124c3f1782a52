#pragma once
// SCM's elastic stiffness Ke [Pa/m] from the unloading parts of plate-sinkage curves.
//
// In SCM a node that unloads springs back elastically, sigma = Ke (z - z_p), z_p its plastic
// sinkage. Every node under a flat plate has the same sinkage history, so a circular plate of
// radius r unloads along F = pi r^2 Ke (z - z_p). Each elastic branch b (one unload run, or one
// reload run below the previous maximum sinkage) gets its own intercept; Ke is shared by every
// branch and plate:
//     F_i = Ke * pi r_i^2 (z_i - z_ref,b) + c_b,     z_p,b = z_ref,b - c_b / (pi r_b^2 Ke).
// That is linear in (Ke, c_1..c_B), with the intercepts as nuisance parameters, so it is solved
// on its own by weighted linear least squares (Eigen's column-pivoting QR) rather than joining
// the Bekker/Mohr/Janosi MCMC: the posterior of Ke under a flat prior is exactly the normal
// N(Ke_hat, se^2) up to the noise-scale estimate, and sampling B extra nuisance intercepts would
// only slow the chains down.
//
// Problems in the data are reported the way a Ceres Summary reports an unusable solve: the fit
// comes back with fitted = false and the reasons in `notes`, the caller keeps Chrono's default Ke
// and the rest of the calibration goes on. (Contradictions inside the file, such as an unload row
// deeper than the deepest sinkage so far, are InputErrors raised by load_plate_csv.)
#include <string>
#include <vector>

#include "bayes/observations.hpp"

namespace terracal::bayes {

// Chrono's default SCM elastic stiffness, kept when the data have no usable unloading.
inline constexpr double kDefaultElasticStiffness = 4e7;  // Pa/m

struct ElasticBranch {
  double radius = 0;  // m
  PlatePhase phase = PlatePhase::kUnload;
  int first_line = 0;          // line in the file of the branch's first row
  int rows = 0;                // rows used (force > 0)
  double plastic_sinkage = 0;  // z_p [m] at the fitted Ke
};

struct ElasticFit {
  bool fitted = false;                   // false: ke is the default and notes say why
  double ke = kDefaultElasticStiffness;  // Pa/m: the least-squares estimate, or the default
  double sd = 0;                         // standard error of ke [Pa/m] (0 when not fitted)
  int rows = 0, dof = 0;                 // rows used, residual degrees of freedom (rows - 1 - branches)
  double noise_sd = 0;                   // residual sd of the weighted fit (relative, or N for absolute noise)
  int lift_off_rows = 0;                 // elastic rows with zero force (plate off the soil): not used
  std::vector<ElasticBranch> branches;
  std::vector<std::string> notes;  // what the user must know: ignored branches, why not fitted

  // Quantile p of the normal approximation N(ke, sd^2).
  double quantile(double p) const;
};

// Fits Ke to every `unload` row and to `reload` rows at or below the previous maximum sinkage of
// their plate (PlatePoint::fitted == false). Rows with zero force are lift-off, not elastic, and
// are left out. Weights follow the calibrator's noise model: relative noise weights each row by
// max(F, 1 % of its plate's largest force), absolute noise weights every row equally.
ElasticFit fit_elastic_stiffness(const PlateData& plate, bool relative_noise = true);

}  // namespace terracal::bayes
