// `terracal campaign SPEC.json --out DIR [--retry-failed] [--shard i/N]` and `terracal campaign --status DIR`.
#include <cstdio>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "apps/campaign_mpi.hpp"
#include "apps/campaign_run.hpp"
#include "apps/commands.hpp"
#include "apps/out_dir.hpp"
#include "core/errors.hpp"

namespace terracal::app {
namespace {

// "i/N" with 0 <= i < N.
void parse_shard(const std::string& text, CampaignSettings& s) {
  int i = -1, n = 0;
  char end = 0;
  if (std::sscanf(text.c_str(), "%d/%d%c", &i, &n, &end) != 2 || n < 1 || i < 0 || i >= n)
    throw InputError(fmt::format("--shard {}: expected i/N with 0 <= i < N (e.g. 0/4)", text));
  s.shard = i;
  s.shards = n;
}

}  // namespace

Command add_campaign(CLI::App& app) {
  CLI::App* sub = app.add_subcommand(
      "campaign", "Soils x gravities x wheels through bevameter -> calibrate -> wheel validation; resumable (SQLite)");
  struct Args {
    CampaignSettings s;
    std::string shard, status;
  };
  auto a = std::make_shared<Args>();
  sub->add_option("spec", a->s.spec, "campaign spec (JSON, docs/campaign.md)")->check(CLI::ExistingFile);
  sub->add_option("--out", a->s.out, "campaign folder (campaign.sqlite, jobs/, report.md)");
  sub->add_flag("--retry-failed", a->s.retry_failed, "run the jobs that failed before again");
  sub->add_option("--shard", a->shard, "i/N: run only this share of the soil x gravity groups (job arrays)");
  sub->add_option("--status", a->status, "print the job table of this campaign folder and exit");
  return [a] {
    if (!a->status.empty()) {
      fmt::print("{}", campaign_status(a->status));
      return 0;
    }
    if (a->s.spec.empty()) throw InputError("campaign: SPEC.json is required (or --status DIR)");
    if (a->s.out.empty()) throw InputError("campaign: --out is required");
    if (!a->shard.empty()) parse_shard(a->shard, a->s);
    // Under MPI only rank 0 checks and makes the folder (the ranks' probes would race); the workers get
    // no job before it exists.
    std::unique_ptr<OutDir> out;
    if (mpi_world().rank == 0) out = std::make_unique<OutDir>("--out", a->s.out);
    const CampaignOutcome o = run_campaign(a->s);
    if (mpi_world().rank != 0) return o.failed > 0 ? 1 : 0;  // rank 0 speaks for the campaign
    fmt::print("campaign: {} jobs: {} done ({} run now), {} failed, {} waiting on a failed job; {:.3g} s; report: "
               "{}/report.md\n",
               o.jobs, o.done, o.ran, o.failed, o.blocked, o.wall_seconds, a->s.out);
    return o.failed + o.blocked > 0 ? 1 : 0;
  };
}

}  // namespace terracal::app
