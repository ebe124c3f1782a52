// `terracal study accuracy-cost|stability|effects --solver crm|scm|wong-reece|rom|vehicle [--spec S.json]
// --out DIR`:
// a study's runs as a campaign (resumable, spread over MPI ranks like `terracal campaign`), then its
// report.
#include <algorithm>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "apps/campaign_db.hpp"
#include "apps/campaign_mpi.hpp"
#include "apps/campaign_run.hpp"
#include "apps/cli_checks.hpp"
#include "apps/commands.hpp"
#include "apps/out_dir.hpp"
#include "apps/study_report.hpp"
#include "apps/study_spec.hpp"
#include "core/errors.hpp"

namespace terracal::app {

Command add_study(CLI::App& app) {
  CLI::App* sub = app.add_subcommand(
      "study", "Accuracy against cost, stability or effects of one solver, as a resumable campaign; report.md");
  struct Args {
    std::string kind, solver, spec;
    CampaignSettings s;
  };
  auto a = std::make_shared<Args>();
  sub->add_option("study", a->kind, "accuracy-cost, stability or effects")->required();
  sub->add_option("--solver", a->solver, "crm, scm, wong-reece, rom or vehicle")->required();
  sub->add_option("--spec", a->spec, "study spec (JSON, docs/study.md); default: the solver's embedded one")
      ->check(CLI::ExistingFile);
  sub->add_option("--out", a->s.out, "study folder (report.md, campaign.sqlite, jobs/)")->required();
  sub->add_flag("--retry-failed", a->s.retry_failed, "run the runs that failed before again");
  return [a] {
    StudyKind kind{};
    if (a->kind == "accuracy-cost") kind = StudyKind::kAccuracyCost;
    else if (a->kind == "stability") kind = StudyKind::kStability;
    else if (a->kind == "effects") kind = StudyKind::kEffects;
    else throw InputError(fmt::format("study '{}': expected accuracy-cost, stability or effects", a->kind));
    const auto it = std::find(kStudySolvers.begin(), kStudySolvers.end(), a->solver);
    if (it == kStudySolvers.end())
      throw InputError(fmt::format("--solver {}: expected crm, scm, wong-reece, rom or vehicle", a->solver));
    const auto solver = static_cast<StudySolver>(it - kStudySolvers.begin());
    const StudySpec spec = read_study_spec(kind, solver, a->spec);  // refuses a bad spec before anything
    const auto jobs = study_jobs(spec);
    std::unique_ptr<OutDir> out;
    if (mpi_world().rank == 0) out = std::make_unique<OutDir>("--out", a->s.out);
    const CampaignOutcome o = run_jobs(a->s, jobs, spec.merged.dump(2) + "\n", [&](const CampaignDb& db) {
      write_study_report(a->s.out, spec, jobs, db);
    });
    if (mpi_world().rank != 0) return 0;
    fmt::print("study {} ({}): {} runs: {} done ({} run now), {} failed; {:.3g} s; report: {}/report.md\n", a->kind,
               a->solver, o.jobs, o.done, o.ran, o.failed, o.wall_seconds, a->s.out);
    // A stability study's failed runs are its findings, not its failure.
    return kind != StudyKind::kStability && o.failed > 0 ? 1 : 0;
  };
}

}  // namespace terracal::app
