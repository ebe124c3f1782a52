#include <map>
#include <memory>

#include <fmt/format.h>

#include "apps/calibration_run.hpp"
#include "apps/cli_checks.hpp"
#include "apps/commands.hpp"
#include "apps/out_dir.hpp"

namespace terracal::app {

namespace {
struct CalibrateArgs {
  CalibrationFiles files;
  CalibrationSettings settings;
};
}  // namespace

Command add_calibrate(CLI::App& app) {
  auto* sub = app.add_subcommand("calibrate",
                                 "Fit SCM (Bekker-Wong-Janosi) parameters and their posterior to bevameter curves "
                                 "and, optionally, single-wheel curves");
  auto a = std::make_shared<CalibrateArgs>();
  CalibrationFiles& f = a->files;
  CalibrationSettings& s = a->settings;
  sub->add_option("--plate", f.plate_csv, "plate-sinkage curves: plate_radius_m,sinkage_m,force_N[,phase]")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--shear", f.shear_csv,
                  "annulus-shear curves: inner_radius_m,outer_radius_m,normal_load_N,angle_rad,torque_Nm")
      ->check(CLI::ExistingFile);
  sub->add_option("--wheel", f.wheel_csv,
                  "single-wheel curves (wheel.csv of `terracal wheel`): slip,load_N,dbp_N,torque_Nm,sinkage_m; fits "
                  "the slip-sinkage S as well")
      ->check(CLI::ExistingFile);
  sub->add_option("--wheel-spec", f.wheel_spec,
                  "the wheel of --wheel (JSON, docs/formats.md 'Wheel'); default: the run.json beside it")
      ->check(CLI::ExistingFile);
  sub->add_option("--out", s.out_dir, "output folder (scm_params.json, posterior.h5, summary.txt, PNG plots)")
      ->required();
  using R = CalibrationRanges;
  add_seed_option(sub, s.seed, "random seed: the same seed gives byte-identical outputs");
  sub->add_option("--chains", s.chains, fmt::format("independent MCMC chains, {} to {}", R::kMinChains, R::kMaxChains))
      ->transform(whole_number<int>())
      ->capture_default_str();
  sub->add_option("--min-ess", s.min_ess, "bulk effective sample size required for every parameter")
      ->check(in_range(R::kMinEss))
      ->capture_default_str();
  sub->add_option("--max-draws", s.max_draws,
                  fmt::format("draw cap per chain ({} to {}); reaching it is reported as not converged", R::kMinDraws,
                              R::kMaxDraws))
      ->transform(whole_number<long>())
      ->capture_default_str();
  sub->add_option("--priors", f.priors_json, "priors file (JSON): bounds, normal/lognormal priors, fixed parameters")
      ->check(CLI::ExistingFile);
  const std::map<std::string, bayes::SamplerKind> samplers{{"dram", bayes::SamplerKind::kDram},
                                                           {"ensemble", bayes::SamplerKind::kEnsemble}};
  add_choice(sub, "--sampler", s.sampler, samplers,
             "dram (delayed-rejection adaptive Metropolis) or ensemble (affine-invariant)");
  const std::map<std::string, bayes::NoiseModel> noises{{"relative", bayes::NoiseModel::kRelative},
                                                        {"absolute", bayes::NoiseModel::kAbsolute}};
  add_choice(sub, "--noise", s.noise, noises, "noise model: relative (sd grows with the signal) or absolute");
  const std::map<std::string, bool> correlations{{"white", false}, {"ar1", true}};
  add_choice(sub, "--noise-correlation", s.correlated_noise, correlations,
             "white (every row independent) or ar1 (each test type counts as N / tau rows, tau from its residuals' "
             "lag-one correlation)")
      ->default_str("white");
  const std::map<std::string, bayes::AnnulusLaw> annulus_laws{{"shared", bayes::AnnulusLaw::kShared},
                                                              {"scaled", bayes::AnnulusLaw::kScaled}};
  add_choice(sub, "--annulus-law", s.annulus_law, annulus_laws,
             "with --shear and --wheel: shared (the annulus follows the set's c, phi, k) or scaled (the annulus's "
             "strength is the set's over a fitted ratio R, with its own Janosi k: it tells only how strength grows "
             "with load)")
      ->default_str("shared");
  sub->add_option("--elastic-stiffness", s.elastic_stiffness,
                  "the set's SCM elastic stiffness Ke [Pa/m]; 0: fitted to the plates' unload rows (Chrono's 4e7 "
                  "without them). Given, the plates' fit is still reported, and wheel curves see the given Ke")
      ->check(off_or_in_range(CalibrationRanges::kElasticStiffness))
      ->capture_default_str();
  sub->add_flag("!--no-plots", s.plots, "skip the PNG plots");
  return [a] {
    const OutDir out = prepare_out_dir("--out", a->settings.out_dir);
    return run_calibration(read_calibration_files(a->files), a->settings).converged ? 0 : 1;
  };
}

}  // namespace terracal::app
