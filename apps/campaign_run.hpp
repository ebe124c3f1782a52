#pragma once
// `terracal campaign`: runs a campaign's jobs (campaign_spec.hpp), each as a terracal command in its
// own process, its state in DIR/campaign.sqlite (campaign_db.hpp). A job writes into a temporary
// folder that is renamed to its final name once the command succeeded, so a finished job's folder is
// complete; a job found "running" when a campaign starts was cut off (a killed process) and runs again.
#include <string>

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

// The table of every job's state (`terracal campaign --status DIR`); throws InputError when DIR holds
// no campaign.
std::string campaign_status(const std::string& dir);

}  // namespace terracal::app
