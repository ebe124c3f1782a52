#include "apps/campaign_run.hpp"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <chrono>
#include <cstring>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "apps/campaign_db.hpp"
#include "apps/campaign_mpi.hpp"
#include "apps/campaign_report.hpp"
#include "apps/campaign_spec.hpp"
#include "core/atomic_file.hpp"
#include "core/errors.hpp"

namespace terracal::app {
namespace fs = std::filesystem;
namespace {

// The job's arguments with "@0" (the folder of the first job it needs) filled in.
std::vector<std::string> resolved_args(const CampaignJob& job, const std::vector<CampaignJob>& jobs,
                                       const std::string& root, const std::string& out) {
  std::vector<std::string> a = job_command_line(job, out);
  for (auto& x : a) {
    if (x.rfind("@0/", 0) == 0) x = (fs::path(root) / jobs[job.needs.at(0)].dir / x.substr(3)).string();
    if (x.rfind("@out/", 0) == 0) x = (fs::path(root) / x.substr(5)).string();
  }
  return a;
}

// Runs `terracal ARGS` (this program) with stdout and stderr into `log`; returns its exit status
// (128 + signal when a signal ended it). The job dies with the campaign's process (PR_SET_PDEATHSIG):
// a killed campaign leaves no job running on, which a restart would race for the job's folder.
int run_child(const std::vector<std::string>& args, const std::string& log, int gpu) {
  std::vector<std::string> copy = args;
  std::vector<char*> argv;
  std::string self = "terracal";
  argv.push_back(self.data());
  for (auto& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) throw RunError(fmt::format("campaign: cannot start a job: {}", std::strerror(errno)));
  if (pid == 0) {  // the child: only async-signal-safe calls until exec
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(137);  // the campaign died before the line above
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    if (fd < 0) _exit(126);
    dup2(fd, 1);
    dup2(fd, 2);
    close(fd);
    if (gpu >= 0) setenv("CUDA_VISIBLE_DEVICES", std::to_string(gpu).c_str(), 1);  // the rank's own GPU
    execv("/proc/self/exe", argv.data());
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw RunError(fmt::format("campaign: waiting for a job: {}", std::strerror(errno)));
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}


}  // namespace

JobOutcome run_campaign_job(const CampaignJob& job, const std::vector<CampaignJob>& jobs, const std::string& out,
                            const std::string& worker, int gpu) {
  const fs::path final_dir = fs::path(out) / job.dir;
  const fs::path tmp = final_dir.string() + ".tmp";
  fs::remove_all(tmp);  // a run cut off before its rename
  fs::remove_all(final_dir);
  fs::create_directories(tmp.parent_path());
  for (const auto& [rel, content] : job.writes) {
    fs::create_directories((fs::path(out) / rel).parent_path());
    write_text_atomically((fs::path(out) / rel).string(), content);
  }
  const std::string log = final_dir.string() + ".log";
  write_text_atomically(log, fmt::format("campaign job {} {} on {}\n", job.stage, job.label, worker));
  const auto t0 = std::chrono::steady_clock::now();
  const int rc = run_child(resolved_args(job, jobs, out, tmp.string()), log, gpu);
  JobOutcome o{rc, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), ""};
  if (rc == 0 && fs::is_directory(tmp)) {
    fs::rename(tmp, final_dir);
    fs::rename(log, final_dir / "log.txt");
  } else {
    if (o.rc == 0) o.rc = 1;  // exit 0 without an output folder
    fs::remove_all(tmp);
    o.error = job_error(rc, log);
  }
  return o;
}

std::unique_ptr<CampaignDb> open_campaign(const CampaignSettings& s, const std::vector<CampaignJob>& jobs,
                                          const std::string& spec_text) {
  fs::create_directories(s.out);
  write_text_atomically(s.out + "/spec.json", spec_text);
  auto db = std::make_unique<CampaignDb>(s.out + "/campaign.sqlite");
  for (const auto& j : jobs) db->add(j.key, j.stage, j.label, j.dir);
  return db;
}

std::string job_error(int rc, const std::string& log) {
  std::ifstream in(log);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  // "[10:58:26] error SCM: ..." -> "SCM: ...": the log's time and level say nothing in a table.
  if (last.size() > 11 && last[0] == '[' && last[9] == ']')
    if (const auto space = last.find(' ', 11); space != std::string::npos) last = last.substr(space + 1);
  return fmt::format("exit {}: {}", rc, last);
}

std::string eta_text(double seconds) {
  const long t = static_cast<long>(seconds + 0.5);
  return t >= 3600 ? fmt::format("{}:{:02}:{:02}", t / 3600, t / 60 % 60, t % 60) : fmt::format("{}:{:02}", t / 60, t % 60);
}

CampaignOutcome run_campaign(const CampaignSettings& s) {
  const CampaignSpec spec = read_campaign_spec(s.spec);  // refuses a bad spec before anything is made
  const std::vector<CampaignJob> jobs = campaign_jobs(spec);
  std::ifstream in(s.spec);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return run_jobs(s, jobs, text, [&](const CampaignDb& db) { write_campaign_report(s.out, spec, jobs, db); });
}

CampaignOutcome run_jobs(const CampaignSettings& s, const std::vector<CampaignJob>& jobs, const std::string& spec_text,
                         const JobsReport& report) {
  const auto start = std::chrono::steady_clock::now();
  if (const MpiWorld w = mpi_world(); w.size > 1) return run_campaign_mpi(s, jobs, spec_text, report, w);
  const std::unique_ptr<CampaignDb> book = open_campaign(s, jobs, spec_text);
  CampaignDb& db = *book;
  CampaignOutcome o;
  std::vector<char> mine(jobs.size());
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    mine[i] = jobs[i].group % s.shards == s.shard;
    o.jobs += mine[i];
  }
  double ran_seconds = 0;
  int left = o.jobs;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    if (!mine[i]) continue;
    const CampaignJob& job = jobs[i];
    const std::string state = db.state(job.key);
    --left;
    if (state == "done" && fs::is_directory(fs::path(s.out) / job.dir)) {
      ++o.done;
      continue;
    }
    if (state == "failed" && !s.retry_failed) {
      ++o.failed;
      continue;
    }
    bool ready = true;
    for (int n : job.needs) ready = ready && db.state(jobs[n].key) == "done";
    if (!ready) {
      ++o.blocked;
      continue;
    }
    db.set_state(job.key, "running", "", 0, "local");
    spdlog::info("campaign: {} {} ({} of {} in this shard)", job.stage, job.label, o.jobs - left, o.jobs);
    const JobOutcome r = run_campaign_job(job, jobs, s.out, "local", -1);
    ran_seconds += r.wall_seconds;
    ++o.ran;
    db.set_state(job.key, r.rc == 0 ? "done" : "failed", r.error, r.wall_seconds, "local");
    (r.rc == 0 ? o.done : o.failed) += 1;
    if (r.rc != 0) spdlog::warn("campaign: {} {} failed ({})", job.stage, job.label, r.error);
    spdlog::info("campaign: {} of {} done, {} failed; about {} left", o.done, o.jobs, o.failed,
                 eta_text(ran_seconds / o.ran * left));
  }
  o.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report(db);
  return o;
}

std::string campaign_status(const std::string& dir) {
  if (!fs::is_regular_file(fs::path(dir) / "campaign.sqlite"))
    throw InputError(fmt::format("--status {}: no campaign.sqlite there; expected a campaign's --out folder", dir));
  CampaignDb db(dir + "/campaign.sqlite");
  std::string t =
      fmt::format("{:<16} {:<28} {:<8} {:>9}  {:<16} {}\n", "stage", "job", "state", "wall [s]", "ran on", "error");
  int done = 0, failed = 0, n = 0;
  for (const auto& r : db.rows()) {
    t += fmt::format("{:<16} {:<28} {:<8} {:>9.3g}  {:<16} {}\n", r.stage, r.label, r.state, r.wall_seconds, r.worker,
                     r.error);
    done += r.state == "done";
    failed += r.state == "failed";
    ++n;
  }
  return t + fmt::format("{} jobs: {} done, {} failed, {} to run\n", n, done, failed, n - done - failed);
}

}  // namespace terracal::app
