// `mpirun -n K terracal campaign`: rank 0 schedules, the other ranks run jobs; the results are those
// of a single-process campaign to the byte, and a rank killed mid-job loses only the jobs in flight.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <regex>
#include <string>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "../skip.hpp"
#include "cli_runner.hpp"
#include "tests/test_paths.hpp"

using namespace terracal::test;
namespace fs = std::filesystem;

namespace {

const std::string kWheel = R"({"radius": 0.47, "width": 0.25, "mass": 108, "angular_velocity": 1.0})";

// The demo's dry sand and the same with a friction angle of 32 degrees, at two gravities, one wheel.
void write_campaign(const std::string& dir) {
  write(dir + "/wheel.json", kWheel);
  auto j = nlohmann::json::parse(read_file(demo_data("truth.json")));
  j["Soil parameters"]["Mohr friction limit"] = 32;
  write(dir + "/sand2.json", j.dump(2));
  write(dir + "/spec.json", R"({"soils": [{"name": "sand", "scm": ")" + demo_data("truth.json") +
                                R"("}, {"name": "sand2", "scm": "sand2.json"}], "gravities": [9.81, 3.71], "wheels": [{"name": "w", "wheel": "wheel.json"}], "options": {"bevameter": {"shear-loads": [245, 490, 736], "no-plots": true}, "calibrate": {"min-ess": 200, "no-plots": true}, "wheel": {"slips": [0.1, 0.4], "duration": 1, "no-plots": true}}})");
}

std::string mpirun(int ranks) {
  return fmt::format("mpirun --allow-run-as-root --oversubscribe -n {} {}", ranks, terracal::test::terracal_exe());
}

bool have_mpi() {
#ifdef TERRACAL_HAVE_MPI
  return std::system("command -v mpirun > /dev/null 2>&1") == 0;
#else
  return false;
#endif
}

// Every result file of campaign `a` equals campaign `b`'s: CSV to the byte, calibrations in their
// parameters and posterior (their "Fit" block names the campaign's own paths).
void check_same_results(const fs::path& a, const fs::path& b) {
  int compared = 0;
  for (const auto& e : fs::recursive_directory_iterator(a / "jobs")) {
    const fs::path rel = fs::relative(e.path(), a);
    const std::string name = e.path().filename().string();
    if (e.path().extension() == ".csv") {
      INFO(rel.string());
      CHECK(read_file(e.path().string()) == read_file((b / rel).string()));
      ++compared;
    } else if (name == "scm_params.json") {
      const auto ja = nlohmann::json::parse(read_file(e.path().string()));
      const auto jb = nlohmann::json::parse(read_file((b / rel).string()));
      INFO(rel.string());
      CHECK(ja["Soil parameters"] == jb["Soil parameters"]);
      CHECK(ja["Posterior"] == jb["Posterior"]);
      ++compared;
    }
  }
  CHECK(compared >= 4 * 2 + 4 + 8);  // plate and shear, scm_params.json, wheel.csv (calibrated, reference), ...
}

// Sends SIGKILL to the campaign process of MPI rank `rank` (found by its environment) whose command
// line holds `out` (this test's campaign, not another test's running beside it); false when none.
bool kill_rank(int rank, const std::string& out) {
  const std::string want = "OMPI_COMM_WORLD_RANK=" + std::to_string(rank);
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string pid = e.path().filename().string();
    if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
    std::string cmd = read_file(e.path().string() + "/cmdline"), env = read_file(e.path().string() + "/environ");
    std::replace(cmd.begin(), cmd.end(), '\0', ' ');
    if (cmd.find(" campaign ") == std::string::npos || cmd.find(out) == std::string::npos) continue;
    std::size_t at = 0;
    for (std::size_t end; (end = env.find('\0', at)) != std::string::npos; at = end + 1)
      if (env.compare(at, end - at, want) == 0) return std::system(("kill -9 " + pid).c_str()) == 0;
  }
  return false;
}

// Waits (up to 30 s) until the campaign in `out` has four jobs done and another in flight, then kills
// its rank `rank`; false when that moment never came.
bool kill_rank_mid_job(int rank, const std::string& out) {
  for (int i = 0; i < 6000; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    int done = 0, tmp = 0;
    if (fs::exists(out + "/jobs"))
      for (const auto& e : fs::recursive_directory_iterator(out + "/jobs")) {
        done += e.path().filename() == "log.txt";
        tmp += e.path().string().ends_with(".tmp");
      }
    if (done >= 4 && tmp > 0 && kill_rank(rank, out)) return true;
  }
  return false;
}

int count_of(const std::string& text, const std::string& word) {
  int n = 0;
  for (auto at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("campaign under MPI: 2 and 3 ranks give the single process's results to the byte",
          "[cli][campaign][mpi]") {
  if (!have_mpi()) {
    report_skip("campaign over MPI", "this build has no MPI, or mpirun is not on the PATH");
    return;
  }
  const ScratchDir scratch("campaign_mpi");
  const std::string dir = scratch.str();
  write_campaign(dir);
  REQUIRE(run_cli("campaign " + dir + "/spec.json --out " + dir + "/one", dir).exit_code == 0);
  for (int ranks : {2, 3}) {
    const std::string out = fmt::format("{}/ranks{}", dir, ranks);
    const std::string cmd = fmt::format("{} campaign {}/spec.json --out {} > {}/log.txt 2>&1", mpirun(ranks), dir, out, dir);
    const int rc = std::system(cmd.c_str());
    INFO(ranks << " ranks: " << read_file(dir + "/log.txt"));
    REQUIRE(rc == 0);
    check_same_results(dir + "/one", out);
    // Every job ran on a worker rank, never on the scheduler.
    const CliResult st = run_cli("campaign --status " + out, dir);
    CHECK(count_of(st.out, "rank ") == 16);
    CHECK(count_of(st.out, "rank 0") == 0);
    if (ranks == 3) CHECK(count_of(st.out, "rank 2") > 0);
  }
}

TEST_CASE("campaign under MPI: a rank killed mid-job ends the run; starting again reruns the jobs in flight only",
          "[cli][campaign][mpi]") {
  if (!have_mpi()) {
    report_skip("campaign over MPI", "this build has no MPI, or mpirun is not on the PATH");
    return;
  }
  const ScratchDir scratch("campaign_mpi_kill");
  const std::string dir = scratch.str();
  write_campaign(dir);
  const std::string out = dir + "/c";
  REQUIRE(std::system(fmt::format("{} campaign {}/spec.json --out {} > {}/log.txt 2>&1 &", mpirun(3), dir, out, dir)
                          .c_str()) == 0);
  // Once four jobs are done and another is in flight, kill worker rank 1. OpenMPI then ends every rank,
  // and each rank's job dies with it.
  REQUIRE(kill_rank_mid_job(1, out));
  for (int i = 0; i < 400 && std::system(("pgrep -f 'campaign .*" + out + "' > /dev/null").c_str()) == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(25));  // mpirun ends the other ranks
  const CliResult before = run_cli("campaign --status " + out, dir);
  const int done_before = count_of(before.out, " done ");
  const int in_flight = count_of(before.out, " running ");
  INFO(before.out);
  CHECK(in_flight >= 1);
  CHECK(in_flight <= 2);  // one job per worker rank
  const CliResult r = run_cli("campaign " + dir + "/spec.json --out " + out, dir);
  INFO(r.out << r.err);
  CHECK(r.exit_code == 0);
  CHECK(r.out.find(fmt::format("16 done ({} run now)", 16 - done_before)) != std::string::npos);
  for (const auto& e : fs::recursive_directory_iterator(out + "/jobs")) CHECK(!e.path().string().ends_with(".tmp"));
}

TEST_CASE("study under MPI: 3 ranks give the single process's runs to the byte", "[cli][study][mpi]") {
  if (!have_mpi()) {
    report_skip("study over MPI", "this build has no MPI, or mpirun is not on the PATH");
    return;
  }
  const ScratchDir scratch("study_mpi");
  const std::string dir = scratch.str();
  REQUIRE(run_cli("study stability --solver rom --out " + dir + "/one", dir).exit_code == 0);
  const std::string cmd =
      fmt::format("{} study stability --solver rom --out {}/three > {}/log.txt 2>&1", mpirun(3), dir, dir);
  const int rc = std::system(cmd.c_str());
  INFO(read_file(dir + "/log.txt"));
  REQUIRE(rc == 0);
  CHECK(read_file(dir + "/log.txt").find("on rank 2") != std::string::npos);  // the workers ran the runs
  int compared = 0;
  for (const auto& e : fs::recursive_directory_iterator(fs::path(dir) / "one" / "jobs"))
    if (e.path().filename() == "trajectory.csv") {
      const fs::path rel = fs::relative(e.path(), fs::path(dir) / "one");
      INFO(rel.string());
      CHECK(read_file(e.path().string()) == read_file((fs::path(dir) / "three" / rel).string()));
      ++compared;
    }
  CHECK(compared == 16);  // the base and the 15 runs of the default sweeps
}

TEST_CASE("campaign under mpirun --enable-recovery: a killed rank's job goes back to the queue, the run finishes",
          "[cli][campaign][mpi]") {
  if (!have_mpi()) {
    report_skip("campaign over MPI with recovery", "this build has no MPI, or mpirun is not on the PATH");
    return;
  }
  const ScratchDir scratch("campaign_mpi_recover");
  const std::string dir = scratch.str();
  write_campaign(dir);
  const std::string out = dir + "/c";
  REQUIRE(std::system(fmt::format("(mpirun --allow-run-as-root --oversubscribe --enable-recovery -n 3 {} campaign "
                                  "{}/spec.json --out {} > {}/log.txt 2>&1; echo \"rc=$?\" >> {}/log.txt) &",
                                  terracal::test::terracal_exe(), dir, out, dir, dir)
                          .c_str()) == 0);
  REQUIRE(kill_rank_mid_job(1, out));
  for (int i = 0; i < 2400 && read_file(dir + "/log.txt").find("rc=") == std::string::npos; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const std::string log = read_file(dir + "/log.txt");
  INFO(log);
  // The scheduler saw the rank die; rank 2 ran the rest, the dead rank's job included; mpirun ended well.
  CHECK(log.find("rank 1 (CPU) died") != std::string::npos);
  CHECK(log.find("16 jobs: 16 done (16 run now)") != std::string::npos);
  CHECK(log.find("rc=0") != std::string::npos);
  for (const auto& e : fs::recursive_directory_iterator(out + "/jobs")) CHECK(!e.path().string().ends_with(".tmp"));
}
