// terracal validate-rom: posterior-predictive runs of a calibrated ROM (calibrate-rom's output folder)
// on reference manoeuvres (apps/rom_validation.hpp); writes report.md, summary.json and the bands.
#include <memory>

#include <fmt/format.h>

#include "apps/cli_checks.hpp"
#include "apps/commands.hpp"
#include "apps/out_dir.hpp"
#include "apps/rom_choices.hpp"
#include "apps/rom_validation.hpp"

namespace terracal::app {

namespace {
struct ValidateRomArgs {
  RomValidationSettings s;
  std::string references, device = "auto";
  CLI::Option* seed = nullptr;
};
}  // namespace

Command add_validate_rom(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "validate-rom", "Posterior-predictive runs of a calibrated reduced-order vehicle on reference manoeuvres");
  auto a = std::make_shared<ValidateRomArgs>();
  RomValidationSettings& s = a->s;
  sub->add_option("--posterior", s.posterior, "output folder of calibrate-rom (rom_params.json, posterior.h5)")
      ->required();
  sub->add_option("--reference", a->references,
                  "reference folders, comma-separated, each with trajectory.csv and inputs.txt")
      ->required();
  sub->add_option("--draws", s.draws, "posterior draws run on each reference (one batch), with replacement")
      ->transform(whole_in(1, 100000000))
      ->capture_default_str();
  sub->add_option("--device", a->device, "where the batches run: cpu, cuda or auto")
      ->check(CLI::IsMember({"cpu", "cuda", "auto"}))
      ->capture_default_str();
  a->seed = add_seed_option(sub, s.seed, "random seed of the draws and the noise; default: the calibration's seed");
  a->seed->default_str("");  // not 1: the calibration's, read from rom_params.json
  sub->add_option("--out", s.out,
                  "output folder (report.md, summary.json, band_*.csv, band_*.png); default: "
                  "<posterior>/validation");
  sub->add_flag("!--no-plots", s.plots, "skip the PNG plots");
  return [a] {
    RomValidationSettings& s = a->s;
    if (s.out.empty()) s.out = s.posterior + "/validation";
    const OutDir out = prepare_out_dir("--out", s.out);
    s.references = rom::split_dirs(a->references, "--reference");
    s.device = batch_device(a->device);
    s.seed_given = a->seed->count() > 0;
    const RomValidationOutcome r = run_rom_validation(s);
    fmt::print(
        "validate-rom: {} draws on {} references ({} failed runs) in {:.3g} s ({:.3g} s in the batches); "
        "written to {}/report.md\n",
        r.draws, r.references.size(), r.failed_runs, r.wall_seconds, r.batch_seconds, r.out);
    return 0;
  };
}

}  // namespace terracal::app
