#pragma once
// A campaign's report.md: every job's state and wall time, the wall time per stage, each soil and
// gravity's calibrated SCM parameters with their 90 % posterior intervals, and the calibrated set's
// single-wheel errors against the reference soil per entry.
#include <string>
#include <vector>

namespace terracal::app {

struct CampaignSpec;
struct CampaignJob;
class CampaignDb;

void write_campaign_report(const std::string& dir, const CampaignSpec& spec, const std::vector<CampaignJob>& jobs,
                           const CampaignDb& db);

}  // namespace terracal::app
