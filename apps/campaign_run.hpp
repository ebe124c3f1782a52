#pragma once
// `terracal campaign`: runs a campaign's jobs (campaign_spec.hpp), each as a terracal command in its
// own process, its state in DIR/campaign.sqlite (campaign_db.hpp). A job writes into a temporary
// folder that is renamed to its final name once the command succeeded, so a finished job's folder is
// complete; a job found "running" when a campaign starts was cut off (a killed process) and runs again.
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace terracal::app {

struct CampaignSettings {
  std::string spec, out;
  bool retry_failed = false;  // run failed jobs again (otherwise recorded and skipped)
  int shard = 0, shards = 1;  // run only the groups (soil x gravity) g with g % shards == shard
};

struct CampaignOutcome {
  int jobs = 0;     // in this shard
  int ran = 0;      // run now
  int done = 0;     // done now or before
  int failed = 0;   // failed (now, or before and not retried)
  int blocked = 0;  // not run: a job they need failed
  double wall_seconds = 0;
};

CampaignOutcome run_campaign(const CampaignSettings& s);

struct CampaignJob;
class CampaignDb;

// What a run of jobs writes once it ends, on rank 0 only: a campaign's report, a study's.
using JobsReport = std::function<void(const CampaignDb& db)>;

// Runs `jobs` into s.out, serially or (started by mpirun) over the ranks, as `terracal campaign`
// does; `spec_text` is written to s.out/spec.json (what made the jobs). s.spec is not read. Every
// command made of jobs (campaign, study) runs through here.
CampaignOutcome run_jobs(const CampaignSettings& s, const std::vector<CampaignJob>& jobs, const std::string& spec_text,
                         const JobsReport& report);

// What the serial run and the MPI one share.
struct JobOutcome {
  int rc = 0;  // the command's exit status (128 + signal)
  double wall_seconds = 0;
  std::string error;  // "exit 2: <the command's last line>" for a failed job
};
// Runs one job (its needs done) into its folder: a temporary one, renamed once the command succeeded;
// `worker` is written at the top of its log; gpu >= 0 sets the job's CUDA_VISIBLE_DEVICES.
JobOutcome run_campaign_job(const CampaignJob& job, const std::vector<CampaignJob>& jobs, const std::string& out,
                            const std::string& worker, int gpu);
// Makes the folder, writes spec.json into it and opens the database with every job added.
std::unique_ptr<CampaignDb> open_campaign(const CampaignSettings& s, const std::vector<CampaignJob>& jobs,
                                          const std::string& spec_text);
std::string eta_text(double seconds);
// "exit 2: <the last line of the job's log>", the log's time and level left out.
std::string job_error(int rc, const std::string& log);

// The table of every job's state (`terracal campaign --status DIR`); throws InputError when DIR holds
// no campaign.
std::string campaign_status(const std::string& dir);

}  // namespace terracal::app
