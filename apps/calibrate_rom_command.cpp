// terracal calibrate-rom: a reduced-order vehicle's parameters and their posterior from reference
// runs (apps/rom_calibration.hpp); writes rom_params.json (loads as --vehicle), posterior.h5 and
// the fits.
#include <filesystem>
#include <map>
#include <memory>

#include <fmt/format.h>

#include "apps/cli_checks.hpp"
#include "apps/commands.hpp"
#include "apps/out_dir.hpp"
#include "apps/rom_calibration.hpp"
#include "apps/rom_choices.hpp"
#include "core/atomic_file.hpp"
#include "core/errors.hpp"

namespace terracal::app {

namespace {
struct CalibrateRomArgs {
  RomCalibrationSettings s;
  std::string references, device = "auto";
};

// Delayed acceptance screens the random-walk move, which runs with Metropolis-Hastings only (i-SIR
// steps without it).
void check_delayed_acceptance(const RomCalibrationSettings& s) {
  if (s.delayed_acceptance <= 0) return;
  const int tries = s.tries > 0 ? s.tries : s.device == rom::BatchDevice::kCuda ? 96 : 1;
  if (s.sampler != bayes::SamplerKind::kIndependence || tries > 1)
    throw InputError(fmt::format(
        "--delayed-acceptance on: expected the independence sampler with Metropolis-Hastings (--tries 1), whose "
        "random-walk move it screens; got --sampler {} with tries {}",
        s.sampler == bayes::SamplerKind::kIndependence ? "independence" : "ensemble", tries));
}

}  // namespace

Command add_calibrate_rom(CLI::App& app) {
  auto* sub = app.add_subcommand("calibrate-rom",
                                 "Fit a reduced-order vehicle's parameters and their posterior to reference runs");
  auto a = std::make_shared<CalibrateRomArgs>();
  RomCalibrationSettings& s = a->s;
  add_choice(sub, "--model", s.model, kRomModels, "vehicle model");
  sub->add_option("--vehicle", s.vehicle, "vehicle file (JSON, terracal's format) or preset: hmmwv, sedan")->required();
  sub->add_option("--reference", a->references,
                  "reference folders, comma-separated, each with trajectory.csv and inputs.txt")
      ->required();
  sub->add_option("--params", s.params_json, "parameters to fit and their priors (JSON); default: docs/rom.md")
      ->check(CLI::ExistingFile);
  sub->add_option("--out", s.out, "output folder (rom_params.json, posterior.h5, fit_*.csv, fit_*.png)")->required();
  add_seed_option(sub, s.seed, "random seed: the same seed gives the same draws");
  const std::map<std::string, bayes::SamplerKind> samplers{{"independence", bayes::SamplerKind::kIndependence},
                                                           {"ensemble", bayes::SamplerKind::kEnsemble}};
  add_choice(sub, "--sampler", s.sampler, samplers,
             "independence (t proposal from the least-squares fit, one batch per step) or ensemble (affine-invariant)");
  sub->add_option("--chains", s.chains,
                  "chains run side by side, one batch per step (ensemble: walkers, even, at least 2 x parameters + 2); "
                  "0: 4, 24 with tries > 1 (ensemble: that minimum)")
      ->check(whole_in(0, 100000))
      ->capture_default_str();
  sub->add_option("--tries", s.tries,
                  "independence sampler: points per chain and step; 1: Metropolis-Hastings, more: i-SIR (chains x "
                  "(tries - 1) runs per batch); 0: 1 on the CPU, 96 on a GPU")
      ->check(whole_in(0, 100000))
      ->capture_default_str();
  sub->add_option("--lookahead", s.lookahead,
                  "independence sampler: steps whose proposals run as one batch; 0: as many as one GPU launch holds "
                  "at once with tries > 1 on a GPU, else 1")
      ->check(whole_in(0, 1000))
      ->capture_default_str();
  const std::map<std::string, int> on_off{{"auto", -1}, {"on", 1}, {"off", 0}};
  add_choice(sub, "--delayed-acceptance", s.delayed_acceptance, on_off,
             "Metropolis-Hastings: test each random-walk move on a t fitted to the posterior first and run only those "
             "that pass (the posterior stays exact); auto: on with tries 1");
  sub->add_option("--min-ess", s.min_ess, "bulk effective sample size required for every parameter")
      ->check(in_range(Range{0, 1e9, true, false}))
      ->capture_default_str();
  sub->add_option("--max-draws", s.max_draws, "draw cap per walker; reaching it is reported as not converged")
      ->check(whole_in(10, 100000000))
      ->capture_default_str();
  sub->add_option("--warmup", s.warmup,
                  "steps per chain discarded before the draws (the proposal adapts in them); -1: 40, 4 with tries > 1")
      ->check(whole_in(-1, 1000000))
      ->capture_default_str();
  sub->add_option("--global-points", s.global_points, "random points of the global search")
      ->check(whole_in(0, 10000000))
      ->capture_default_str();
  sub->add_option("--starts", s.starts,
                  "least-squares starts: the vehicle's own values and the global search's N - 1 best; one round "
                  "each, then the best fit goes on")
      ->check(whole_in(1, 100))
      ->capture_default_str();
  sub->add_option("--step", s.step, "the ROM's fixed step [s]")
      ->check(in_range(Range{1e-5, 0.01, false, false}))
      ->capture_default_str();
  sub->add_option("--device", a->device, "where the batches run: cpu, cuda or auto")
      ->check(CLI::IsMember({"cpu", "cuda", "auto"}))
      ->capture_default_str();
  const std::map<std::string, bool> noises{{"correlated", true}, {"white", false}};
  add_choice(sub, "--noise", s.correlated_noise, noises,
             "residuals correlated along a run (each channel counts as N / tau rows, tau from the least-squares "
             "fit) or white (every row independent)");
  sub->add_flag("!--no-plots", s.plots, "skip the PNG plots");
  return [a] {
    const OutDir out = prepare_out_dir("--out", a->s.out);
    a->s.references = rom::split_dirs(a->references, "--reference");
    a->s.device = batch_device(a->device);
    check_delayed_acceptance(a->s);
    std::filesystem::create_directories(a->s.out);
    const RomCalibrationOutcome r = run_rom_calibration(a->s);
    fmt::print(
        "calibrate-rom: {}; {} ROM runs ({} failed) in {:.3g} s ({:.3g} s in the forward model, {:.3g} s of it in "
        "the batches, {:.3g} s stepping); written to {}/rom_params.json\n",
        r.result.termination, r.runs, r.failed_runs, r.wall_seconds, r.model_seconds, r.forward_seconds,
        r.stepping_seconds, a->s.out);
    return r.result.converged ? 0 : 1;
  };
}

}  // namespace terracal::app
