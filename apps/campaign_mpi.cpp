#include "apps/campaign_mpi.hpp"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <thread>

#include <signal.h>
#include <unistd.h>

#include <cerrno>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "apps/campaign_db.hpp"
#include "core/checksum.hpp"
#include "core/device_selftest.hpp"

#ifdef TERRACAL_HAVE_MPI
#include <mpi.h>
#endif

namespace terracal::app {
namespace fs = std::filesystem;

#ifndef TERRACAL_HAVE_MPI

MpiWorld mpi_world() { return {}; }

CampaignOutcome run_campaign_mpi(const CampaignSettings&, const std::vector<CampaignJob>&, const std::string&,
                                 const JobsReport&, const MpiWorld&) {
  throw std::logic_error("run_campaign_mpi: this build has no MPI");
}

#else

namespace {

bool started_by_mpirun() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(v)) return true;
  return false;
}

int env_int(const char* name, int fallback) {
  const char* v = std::getenv(name);
  return v ? std::atoi(v) : fallback;
}

constexpr int kTagToScheduler = 1, kTagToWorker = 2;

// What rank 0 knows of a worker.
struct Worker {
  pid_t pid = 0;
  double host = 0;  // host_code() of its node
  int job = -1;     // the job it runs, -1 when none
  bool alive = true;
};

// This node's name as a number a message can carry: 52 bits of its hash, exact in a double.
double host_code() {
  char name[MPI_MAX_PROCESSOR_NAME] = {};
  int length = 0;
  MPI_Get_processor_name(name, &length);
  Fnv1a64 h;
  h.add(name, static_cast<std::size_t>(length));
  return static_cast<double>(h.value() & ((std::uint64_t{1} << 52) - 1));
}

// Set once a worker died: MPI_Finalize would wait for it, so the run ends without it.
bool& any_died() {
  static bool died = false;
  return died;
}

// A job's place in rank 0's plan.
enum class Plan { kOther, kPending, kRunning, kDone, kFailed, kBlocked };

// Rank 0: hands the next job whose needs are done to whichever worker asks, records every change in
// the database, and stops the workers once nothing is left that can run.
CampaignOutcome schedule(const CampaignSettings& s, const std::vector<CampaignJob>& jobs, const std::string& spec_text,
                         const JobsReport& report, int size) {
  const auto start = std::chrono::steady_clock::now();
  const std::unique_ptr<CampaignDb> book = open_campaign(s, jobs, spec_text);
  CampaignDb& db = *book;
  CampaignOutcome o;
  std::vector<Plan> plan(jobs.size(), Plan::kOther);
  auto block_dependents = [&](std::size_t failed) {
    for (std::size_t i = failed + 1; i < jobs.size(); ++i)
      for (int n : jobs[i].needs)
        if (n >= 0 && static_cast<std::size_t>(n) < i &&
            (plan[n] == Plan::kFailed || plan[n] == Plan::kBlocked) && plan[i] == Plan::kPending)
          plan[i] = Plan::kBlocked;
  };
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    if (jobs[i].group % s.shards != s.shard) continue;
    ++o.jobs;
    const std::string st = db.state(jobs[i].key);
    plan[i] = st == "done" && fs::is_directory(fs::path(s.out) / jobs[i].dir) ? Plan::kDone
              : st == "failed" && !s.retry_failed                            ? Plan::kFailed
                                                                             : Plan::kPending;
  }
  for (std::size_t i = 0; i < jobs.size(); ++i)
    if (plan[i] == Plan::kFailed) block_dependents(i);
  auto next_ready = [&]() -> int {
    for (std::size_t i = 0; i < jobs.size(); ++i) {
      if (plan[i] != Plan::kPending) continue;
      bool ready = true;
      for (int n : jobs[i].needs) ready = ready && plan[n] == Plan::kDone;
      if (ready) return static_cast<int>(i);
    }
    return -1;
  };
  std::deque<int> idle;
  std::vector<std::string> names(size);
  std::vector<Worker> workers(size);
  int running = 0, live = size - 1;
  double ran_seconds = 0;
  const double host = host_code();
  // A worker whose process is gone (killed, crashed) takes its job with it: the job goes back to the
  // queue and the others carry on. Seen for workers on this node only (by their process id); under
  // mpirun's default a dead rank ends every rank anyway, `--enable-recovery` lets the others go on.
  auto reap_dead = [&] {
    for (int w = 1; w < size; ++w) {
      Worker& k = workers[w];
      if (!k.alive || k.pid <= 0 || k.host != host || !(::kill(k.pid, 0) != 0 && errno == ESRCH)) continue;
      k.alive = false;
      --live;
      idle.erase(std::remove(idle.begin(), idle.end(), w), idle.end());
      if (k.job >= 0) {
        plan[k.job] = Plan::kPending;
        --running;
        db.set_state(jobs[k.job].key, "queued", "", 0, "");
        spdlog::warn("campaign: {} died; its job {} {} goes back to the queue", names[w], jobs[k.job].stage,
                     jobs[k.job].label);
      } else {
        spdlog::warn("campaign: {} died between jobs", names[w]);
      }
      k.job = -1;
      any_died() = true;
    }
  };
  while (live > 0) {
    double msg[6];  // job (-1: ready), exit status, wall time, the worker's GPU (-1: CPU), pid, host
    MPI_Status status;
    int arrived = 0;
    while (live > 0) {
      MPI_Iprobe(MPI_ANY_SOURCE, kTagToScheduler, MPI_COMM_WORLD, &arrived, &status);
      if (arrived) break;
      reap_dead();
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    if (!arrived) break;  // every worker died
    MPI_Recv(msg, 6, MPI_DOUBLE, status.MPI_SOURCE, kTagToScheduler, MPI_COMM_WORLD, &status);
    const int worker = status.MPI_SOURCE;
    // A message sent just before its worker died, read after the worker was found dead: its job is back
    // in the queue already (it runs again), and the worker gets no other.
    if (!workers[worker].alive) continue;
    workers[worker].pid = static_cast<pid_t>(msg[4]);
    workers[worker].host = msg[5];
    const std::string where = msg[3] >= 0 ? fmt::format("rank {} (GPU {})", worker, static_cast<int>(msg[3]))
                                          : fmt::format("rank {} (CPU)", worker);
    names[worker] = where;
    if (msg[0] >= 0) {  // a result
      const auto j = static_cast<std::size_t>(msg[0]);
      const int rc = static_cast<int>(msg[1]);
      --running;
      ++o.ran;
      ran_seconds += msg[2];
      workers[worker].job = -1;
      plan[j] = rc == 0 ? Plan::kDone : Plan::kFailed;
      std::string error;
      if (rc != 0) {
        error = job_error(rc, (fs::path(s.out) / (jobs[j].dir + ".log")).string());
        block_dependents(j);
        spdlog::warn("campaign: {} {} failed on rank {} ({})", jobs[j].stage, jobs[j].label, worker, error);
      }
      db.set_state(jobs[j].key, rc == 0 ? "done" : "failed", error, msg[2], where);
      int left = 0;
      for (Plan p : plan) left += p == Plan::kPending;
      spdlog::info("campaign: {} {} {} on {}; {} to run, {} running; about {} to go", jobs[j].stage, jobs[j].label,
                   rc == 0 ? "done" : "failed", where, left, running,
                   eta_text(ran_seconds / o.ran * left / std::max(1, live)));
    }
    idle.push_back(worker);
    while (!idle.empty()) {
      const int j = next_ready();
      if (j < 0) break;
      plan[j] = Plan::kRunning;
      workers[idle.front()].job = j;
      db.set_state(jobs[j].key, "running", "", 0, names[idle.front()]);
      MPI_Send(&j, 1, MPI_INT, idle.front(), kTagToWorker, MPI_COMM_WORLD);
      idle.pop_front();
      ++running;
    }
    if (running == 0 && next_ready() < 0) {  // nothing runs and nothing can: stop the workers
      const int stop = any_died() ? -2 : -1;  // -2: a rank died, end without MPI_Finalize
      for (int w : idle) MPI_Send(&stop, 1, MPI_INT, w, kTagToWorker, MPI_COMM_WORLD);
      live -= static_cast<int>(idle.size());
      for (int w : idle) workers[w].alive = false;
      idle.clear();
    }
  }
  for (Plan p : plan) {
    o.done += p == Plan::kDone;
    o.failed += p == Plan::kFailed;
    o.blocked += p == Plan::kBlocked;
  }
  o.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report(db);
  return o;
}

// Ranks 1..K-1: ask, run, report, until told to stop.
CampaignOutcome work(const CampaignSettings& s, const std::vector<CampaignJob>& jobs, const MpiWorld& w) {
  const CudaDeviceInfo gpus = cuda_device_info();
  const int gpu = gpus.count > 0 ? w.local_rank % gpus.count : -1;
  const std::string me = gpu >= 0 ? fmt::format("rank {} (GPU {})", w.rank, gpu) : fmt::format("rank {} (CPU)", w.rank);
  CampaignOutcome o;
  double msg[6] = {-1, 0, 0, static_cast<double>(gpu), static_cast<double>(getpid()), host_code()};
  for (;;) {
    MPI_Send(msg, 6, MPI_DOUBLE, 0, kTagToScheduler, MPI_COMM_WORLD);
    int j = -1;
    MPI_Recv(&j, 1, MPI_INT, 0, kTagToWorker, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (j < 0) {
      any_died() = j == -2;
      break;
    }
    const JobOutcome r = run_campaign_job(jobs[j], jobs, s.out, me, gpu);
    ++o.jobs;
    ++o.ran;
    (r.rc == 0 ? o.done : o.failed) += 1;
    msg[0] = j;
    msg[1] = r.rc;
    msg[2] = r.wall_seconds;
  }
  return o;
}

}  // namespace

MpiWorld mpi_world() {
  static MpiWorld world = [] {
    MpiWorld w;
    if (!started_by_mpirun()) return w;
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    std::atexit([] {
      if (!any_died()) MPI_Finalize();  // a dead rank never reaches it: finalising would wait forever
    });
    MPI_Comm_rank(MPI_COMM_WORLD, &w.rank);
    MPI_Comm_size(MPI_COMM_WORLD, &w.size);
    w.local_rank = env_int("OMPI_COMM_WORLD_LOCAL_RANK", env_int("MPI_LOCALRANKID", w.rank));
    return w;
  }();
  return world;
}

CampaignOutcome run_campaign_mpi(const CampaignSettings& s, const std::vector<CampaignJob>& jobs,
                                 const std::string& spec_text, const JobsReport& report, const MpiWorld& w) {
  if (w.rank == 0) return schedule(s, jobs, spec_text, report, w.size);
  // Workers wait until rank 0 has made the folder and the database.
  return work(s, jobs, w);
}

#endif

}  // namespace terracal::app
