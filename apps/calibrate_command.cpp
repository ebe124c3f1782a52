#include <memory>

#include "apps/calibration_run.hpp"
#include "apps/commands.hpp"

namespace terracal::app {

Command add_calibrate(CLI::App& app) {
  auto* sub = app.add_subcommand("calibrate", "Fit SCM (Bekker-Wong-Janosi) parameters and their posterior to bevameter curves");
  auto req = std::make_shared<CalibrationRequest>();
  sub->add_option("--plate", req->plate_csv, "plate-sinkage curves: plate_radius_m,sinkage_m,force_N[,phase]")->required()->check(CLI::ExistingFile);
  sub->add_option("--shear", req->shear_csv, "annulus-shear curves: inner_radius_m,outer_radius_m,normal_load_N,angle_rad,torque_Nm")->check(CLI::ExistingFile);
  sub->add_option("--out", req->out_dir, "output folder (scm_params.json, posterior.h5, summary.txt, PNG plots)")->required();
  sub->add_option("--seed", req->seed, "random seed: the same seed gives byte-identical outputs")->capture_default_str();
  sub->add_option("--chains", req->chains, "independent MCMC chains (>= 4)")->capture_default_str();
  sub->add_option("--min-ess", req->min_ess, "bulk effective sample size required for every parameter")->capture_default_str();
  sub->add_option("--max-draws", req->max_draws, "draw cap per chain; reaching it is reported as not converged")->capture_default_str();
  sub->add_option("--priors", req->priors_json, "priors file (JSON): bounds, normal/lognormal priors, fixed parameters")->check(CLI::ExistingFile);
  sub->add_option("--sampler", req->sampler, "dram (delayed-rejection adaptive Metropolis) or ensemble (affine-invariant)")->capture_default_str();
  sub->add_option("--noise", req->noise, "noise model: relative (sd grows with the signal) or absolute")->capture_default_str();
  sub->add_flag("!--no-plots", req->plots, "skip the PNG plots");
  return [req] { return run_calibration(*req); };
}

}  // namespace terracal::app
