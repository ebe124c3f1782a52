// `terracal pipeline-rom`: full-vehicle runs on a training set -> calibrate a ROM -> validate it on
// other manoeuvres -> accuracy against cost -> report.md (apps/rom_pipeline.hpp).
#include <memory>

#include <fmt/format.h>

#include "apps/cli_checks.hpp"
#include "apps/commands.hpp"
#include "apps/out_dir.hpp"
#include "apps/rom_choices.hpp"
#include "apps/rom_pipeline.hpp"

namespace terracal::app {

namespace {
struct PipelineRomArgs {
  RomPipelineSettings s;
  std::string device = "cpu";
};
}  // namespace

Command add_pipeline_rom(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "pipeline-rom",
      "Full vehicle on training manoeuvres -> calibrate a ROM -> validate on others -> accuracy against cost; report.md");
  auto a = std::make_shared<PipelineRomArgs>();
  RomPipelineSettings& s = a->s;
  sub->add_option("--vehicle", s.vehicle, "full vehicle: file (JSON) or preset hmmwv")->capture_default_str();
  sub->add_option("--rom-vehicle", s.rom_vehicle, "the ROM's starting vehicle (file or preset); default: --vehicle");
  add_choice(sub, "--model", s.model, kRomModels, "the ROM calibrated")->default_str("18dof");
  sub->add_option("--out", s.out, "output folder")->required();
  add_seed_option(sub, s.seed, "random seed of the calibration and the validation draws");
  sub->add_option("--max-draws", s.max_draws, "calibration: draw cap per chain; reaching it is reported as not converged")
      ->check(whole_in(10, 100000000))
      ->capture_default_str();
  sub->add_option("--draws", s.draws, "validation: posterior-predictive draws")
      ->check(whole_in(1, 10000000))
      ->capture_default_str();
  sub->add_option("--device", a->device, "where the ROM batches run: cpu, cuda or auto")
      ->check(CLI::IsMember({"cpu", "cuda", "auto"}))
      ->capture_default_str();
  sub->add_flag("!--no-plots", s.plots, "skip the PNG plots");
  return [a] {
    const OutDir out = prepare_out_dir("--out", a->s.out);
    a->s.device = batch_device(a->device);
    const RomPipelineOutcome r = run_rom_pipeline(a->s);
    fmt::print("pipeline-rom: {} in {:.3g} s (full vehicle {:.3g} s, calibration {:.3g} s, validation {:.3g} s); "
               "written to {}/report.md\n",
               r.converged ? "calibration converged" : "calibration NOT converged", r.total_seconds, r.full_seconds,
               r.calibration_seconds, r.validation_seconds, a->s.out);
    return r.converged ? 0 : 1;
  };
}

}  // namespace terracal::app
