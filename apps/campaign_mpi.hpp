#pragma once
// A campaign spread over MPI ranks (`mpirun -n K terracal campaign ...`): rank 0 schedules jobs from
// the campaign's database, ranks 1..K-1 run them, one job at a time each, one GPU per rank where the
// node has GPUs (the rank's local rank picks it). Without MPI in the build, or when not started by
// mpirun, the world is one process and the campaign runs serially.
#include <vector>

#include "apps/campaign_run.hpp"
#include "apps/campaign_spec.hpp"

namespace terracal::app {

struct MpiWorld {
  int rank = 0, size = 1;
  int local_rank = 0;  // on this node
};

// Initialises MPI once when this process was started by mpirun (OpenMPI's or a PMI launcher's
// environment), finalised at exit; {0, 1, 0} otherwise.
MpiWorld mpi_world();

// Rank 0 returns the campaign's outcome (and writes the report); the other ranks return theirs
// (jobs = the jobs they ran).
CampaignOutcome run_campaign_mpi(const CampaignSettings& s, const std::vector<CampaignJob>& jobs,
                                 const std::string& spec_text, const JobsReport& report, const MpiWorld& world);

}  // namespace terracal::app
