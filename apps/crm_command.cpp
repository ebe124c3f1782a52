// `terracal crm`: run a CRM scene (docs/crm_scene.md) on the CPU or the GPU.
#include <filesystem>
#include <memory>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "apps/cli_checks.hpp"
#include "apps/commands.hpp"
#include "apps/memory_check.hpp"
#include "apps/out_dir.hpp"
#include "apps/terrain_options.hpp"
#include "core/errors.hpp"
#include "highfi/crm/crm_run.hpp"

namespace terracal::app {

namespace {
struct CrmArgs {
  std::string scene, out, cache = "results/runs/bed_cache";
  DeviceChoice device = DeviceChoice::kCpu;
  bool resume = false;
  long record_every = 10;
};
}  // namespace

Command add_crm(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "crm", "Run a CRM (SPH) scene: bodies on a settled soil bed; writes bodies.csv, VTU snapshots, checkpoints");
  auto a = std::make_shared<CrmArgs>();
  sub->add_option("--scene", a->scene, "scene file (JSON, see docs/crm_scene.md)")->required();
  sub->add_option("--out", a->out, "output folder")->required();
  add_device_option(sub, a->device);
  sub->add_option("--cache", a->cache, "folder of settled beds ('' = no cache)")->capture_default_str();
  sub->add_flag("--resume", a->resume, "continue from OUT/checkpoint.h5");
  sub->add_option("--record-every", a->record_every, "steps between rows of bodies.csv")
      ->transform(whole_in(1, 1LL << 40))
      ->capture_default_str();
  return [a] {
    const OutDir out = prepare_out_dir("--out", a->out);
    const CrmScene scene = load_crm_scene(a->scene);
    if (a->resume && !std::filesystem::exists(std::filesystem::path(a->out) / "checkpoint.h5"))
      throw InputError(
          fmt::format("--resume: {}/checkpoint.h5 does not exist; expected the --out of an interrupted run", a->out));
    CrmRunOptions o;
    o.out = a->out;
    o.device = resolve_device(a->device);
    check_crm_memory(scene, o.device,
                     fmt::format("{}: key 'resolution.spacing' {} m", a->scene, scene.numerics.spacing),
                     "a coarser resolution.spacing or a smaller bin.size", true);
    o.cache_dir = a->cache;
    o.resume = a->resume;
    o.record_every = a->record_every;
    const CrmRunSummary s = run_crm_scene(scene, o);
    fmt::print("{} particles, {} steps of {:.4g} s in {:.3g} s wall: {:.3g} particle-steps/s on {}; lost {}\n",
               s.particles, s.steps, s.time_step, s.wall_seconds, s.particle_steps_per_second, s.device, s.lost);
    return 0;
  };
}

}  // namespace terracal::app
