// `terracal campaign`: a small SCM campaign run, resumed, changed, broken and sharded, checked job by
// job against the campaign's database and the commands run on their own.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <set>
#include <filesystem>
#include <regex>
#include <thread>
#include <string>

#include <nlohmann/json.hpp>

#include "apps/campaign_spec.hpp"
#include "cli_runner.hpp"
#include "core/gnuplot.hpp"
#include "tests/test_paths.hpp"

using namespace terracal::test;
namespace fs = std::filesystem;

namespace {

const std::string kWheel = R"({"radius": 0.47, "width": 0.25, "mass": 108, "angular_velocity": 1.0})";

// Two soils (the demo's dry sand, and the same with another friction angle) at two gravities, one wheel.
std::string spec_text(const std::string& gravities, const std::string& second_soil = "sand2.json") {
  return R"({"name": "test", "soils": [{"name": "sand", "scm": ")" + demo_data("truth.json") +
         R"("}, {"name": "sand2", "scm": ")" + second_soil + R"("}], "gravities": )" + gravities +
         R"(, "wheels": [{"name": "w", "wheel": "wheel.json"}], "options": {"bevameter": {"shear-loads": [245, 490, 736], "no-plots": true}, "calibrate": {"min-ess": 200, "no-plots": true}, "wheel": {"slips": [0.1, 0.4], "duration": 1, "no-plots": true}}})";
}

// "campaign: 16 jobs: 16 done (16 run now), 0 failed, 0 waiting on a failed job; ..." -> its numbers.
struct Counts {
  int jobs = -1, done = -1, ran = -1, failed = -1, blocked = -1;
};
Counts counts(const std::string& out) {
  std::smatch m;
  Counts c;
  if (std::regex_search(out, m, std::regex(R"((\d+) jobs: (\d+) done \((\d+) run now\), (\d+) failed, (\d+) waiting)"))) {
    c.jobs = std::stoi(m[1]);
    c.done = std::stoi(m[2]);
    c.ran = std::stoi(m[3]);
    c.failed = std::stoi(m[4]);
    c.blocked = std::stoi(m[5]);
  }
  return c;
}

std::string soil_with_friction(double phi) {
  auto j = nlohmann::json::parse(read_file(demo_data("truth.json")));
  j["Soil parameters"]["Mohr friction limit"] = phi;
  return j.dump(2);
}

// The folder of the one job of `stage` whose label is `label`.
fs::path job_dir(const std::string& root, const std::string& stage, const std::string& label) {
  for (const auto& e : fs::directory_iterator(fs::path(root) / "jobs" / stage)) {
    const std::string n = e.path().filename().string();
    if (e.is_directory() && n.rfind(label + "-", 0) == 0 && n.find('-', label.size() + 1) == std::string::npos)
      return e.path();
  }
  return {};
}

}  // namespace

TEST_CASE("campaign: runs, resumes without recomputing, reruns only what a change touches",
          "[cli][campaign]") {
  const ScratchDir scratch("campaign_resume");
  const std::string dir = scratch.str();
  write(dir + "/wheel.json", kWheel);
  write(dir + "/sand2.json", soil_with_friction(32));
  write(dir + "/spec.json", spec_text("[9.81, 3.71]"));
  const std::string cmd = "campaign " + dir + "/spec.json --out " + dir + "/c";

  CliResult r = run_cli(cmd, dir);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  Counts c = counts(r.out);
  CHECK(c.jobs == 16);
  CHECK(c.ran == 16);
  CHECK(c.done == 16);
  CHECK(fs::exists(dir + "/c/campaign.sqlite"));
  const std::string report = read_file(dir + "/c/report.md");
  CHECK(report.find("16 of 16 jobs done") != std::string::npos);
  CHECK(report.find("| sand2_g3.71 |") != std::string::npos);  // calibrated parameters per soil and gravity
  CHECK(report.find("| sand_g9.81_w |") != std::string::npos);  // wheel errors per entry
  if (terracal::gnuplot_available())  // the report's plots: parameters against gravity, wheel errors, wall per stage
    for (const char* png : {"parameters.png", "wheel_errors.png", "stage_wall.png"}) CHECK(fs::exists(dir + "/c/" + png));

  // A job's outputs are those of the same command run on its own, to the byte.
  const fs::path bev = job_dir(dir + "/c", "bevameter", "sand2_g3.71");
  REQUIRE(!bev.empty());
  REQUIRE(run_cli("bevameter --solver scm --scm " + dir + "/sand2.json --gravity 0 0 -3.71 --test all --shear-loads "
                  "245,490,736 --no-plots --out " + dir + "/alone",
                  dir).exit_code == 0);
  CHECK(read_file((bev / "plate.csv").string()) == read_file(dir + "/alone/plate.csv"));
  CHECK(read_file((bev / "shear.csv").string()) == read_file(dir + "/alone/shear.csv"));

  // Again: nothing runs.
  r = run_cli(cmd, dir);
  c = counts(r.out);
  CHECK(r.exit_code == 0);
  CHECK(c.ran == 0);
  CHECK(c.done == 16);

  // Another gravity adds its 8 jobs; the 16 done stay done.
  write(dir + "/spec.json", spec_text("[9.81, 3.71, 1.62]"));
  r = run_cli(cmd, dir);
  c = counts(r.out);
  CHECK(c.jobs == 24);
  CHECK(c.ran == 8);

  // A changed soil file reruns that soil's 12 jobs (bevameter, calibrate, wheel, reference at 3 gravities).
  write(dir + "/sand2.json", soil_with_friction(33));
  r = run_cli(cmd, dir);
  c = counts(r.out);
  CHECK(c.ran == 12);
  CHECK(c.done == 24);
}

TEST_CASE("campaign: a failed job is recorded and the rest goes on; --retry-failed runs it again",
          "[cli][campaign]") {
  const ScratchDir scratch("campaign_failure");
  const std::string dir = scratch.str();
  write(dir + "/wheel.json", kWheel);
  write(dir + "/bad.json", R"({"Type": "SCM", "Soil parameters": {"Bekker Kphi": -5}})");  // the rigs refuse it
  write(dir + "/spec.json", spec_text("[9.81]", "bad.json"));
  const std::string cmd = "campaign " + dir + "/spec.json --out " + dir + "/c";
  CliResult r = run_cli(cmd, dir);
  Counts c = counts(r.out);
  INFO(r.out << r.err);
  CHECK(r.exit_code == 1);
  CHECK(c.jobs == 8);
  CHECK(c.done == 4);     // sand's four
  CHECK(c.failed == 2);   // sand2's bevameter and reference wheel
  CHECK(c.blocked == 2);  // sand2's calibration and calibrated wheel, which need the bevameter's curves
  const CliResult st = run_cli("campaign --status " + dir + "/c", dir);
  CHECK(st.exit_code == 0);
  CHECK(st.out.find("exit 2: ") != std::string::npos);  // the job's exit code and its message
  CHECK(read_file(dir + "/c/report.md").find("| failed |") != std::string::npos);

  r = run_cli(cmd, dir);
  CHECK(counts(r.out).ran == 0);  // failed jobs are not retried unasked
  r = run_cli(cmd + " --retry-failed", dir);
  CHECK(counts(r.out).ran == 2);
}

TEST_CASE("campaign: kill -9 mid-job loses that job only; starting again finishes the campaign",
          "[cli][campaign]") {
  const ScratchDir scratch("campaign_kill");
  const std::string dir = scratch.str();
  write(dir + "/wheel.json", kWheel);
  write(dir + "/sand2.json", soil_with_friction(32));
  write(dir + "/spec.json", spec_text("[9.81, 3.71]"));
  const std::string cmd = terracal::test::terracal_exe() + " campaign " + dir + "/spec.json --out " + dir + "/c";
  REQUIRE(std::system((cmd + " > " + dir + "/first.log 2>&1 & echo $! > " + dir + "/pid").c_str()) == 0);
  // Wait until the fifth job is in flight (its temporary folder exists), then kill the campaign.
  bool seen = false;
  for (int i = 0; i < 6000 && !seen; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    int done = 0;
    if (fs::exists(dir + "/c/jobs"))
      for (const auto& e : fs::recursive_directory_iterator(dir + "/c/jobs")) {
        const std::string n = e.path().filename().string();
        done += n == "log.txt";
        seen = seen || (done >= 4 && n.ends_with(".tmp"));
      }
  }
  REQUIRE(seen);
  REQUIRE(std::system(("kill -9 $(cat " + dir + "/pid)").c_str()) == 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const CliResult st = run_cli("campaign --status " + dir + "/c", dir);
  INFO(st.out);
  CHECK(st.out.find("running") != std::string::npos);  // the job in flight, as the kill left it

  const CliResult r = run_cli("campaign " + dir + "/spec.json --out " + dir + "/c", dir);
  const Counts c = counts(r.out);
  INFO(r.out << r.err);
  CHECK(r.exit_code == 0);
  CHECK(c.done == 16);
  CHECK(c.ran >= 1);
  CHECK(c.ran <= 12);  // at least four were done before the kill
  for (const auto& e : fs::recursive_directory_iterator(dir + "/c/jobs")) CHECK(!e.path().string().ends_with(".tmp"));
}

TEST_CASE("campaign: shards split the soil x gravity groups and together make the whole campaign",
          "[cli][campaign]") {
  const ScratchDir scratch("campaign_shards");
  const std::string dir = scratch.str();
  write(dir + "/wheel.json", kWheel);
  write(dir + "/sand2.json", soil_with_friction(32));
  write(dir + "/spec.json", spec_text("[9.81, 3.71]"));
  const std::string cmd = "campaign " + dir + "/spec.json --out " + dir + "/c";
  const Counts a = counts(run_cli(cmd + " --shard 0/2", dir).out);
  const Counts b = counts(run_cli(cmd + " --shard 1/2", dir).out);
  CHECK(a.jobs == 8);
  CHECK(b.jobs == 8);
  CHECK(a.ran + b.ran == 16);
  const Counts all = counts(run_cli(cmd, dir).out);
  CHECK(all.ran == 0);
  CHECK(all.done == 16);
}

TEST_CASE("campaign: a CRM soil's copy per gravity carries that gravity; keys follow inputs", "[cli][campaign]") {
  const ScratchDir scratch("campaign_jobs");
  const std::string dir = scratch.str();
  write(dir + "/wheel.json", kWheel);
  const std::string soil = terracal::test::source_dir() + "/studies/pipeline/bevameter_soil_2022.json";
  write(dir + "/spec.json", R"({"soils": [{"name": "bed", "crm": ")" + soil +
                                R"("}], "gravities": [9.81, 1.62], "wheels": [{"name": "w", "wheel": "wheel.json"}]})");
  const auto jobs = terracal::app::campaign_jobs(terracal::app::read_campaign_spec(dir + "/spec.json"));
  REQUIRE(jobs.size() == 8);
  int checked = 0;
  for (const auto& j : jobs) {
    if (j.stage != "bevameter" && j.stage != "wheel_reference") continue;
    REQUIRE(j.writes.size() == 1);
    const double g = j.label.find("_g1.62") != std::string::npos ? 1.62 : 9.81;
    const auto m = nlohmann::json::parse(j.writes[0].second);
    CHECK(m["gravity"][2].get<double>() == -g);
    CHECK(m["density"] == nlohmann::json::parse(read_file(soil))["density"]);
    CHECK(std::find(j.args.begin(), j.args.end(), "@out/" + j.writes[0].first) != j.args.end());
    ++checked;
  }
  CHECK(checked == 4);
  // The same spec gives the same keys; every job's key is its own.
  const auto again = terracal::app::campaign_jobs(terracal::app::read_campaign_spec(dir + "/spec.json"));
  std::set<std::string> keys;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    CHECK(jobs[i].key == again[i].key);
    keys.insert(jobs[i].key);
  }
  CHECK(keys.size() == jobs.size());
}

// The vehicles' stages: each entry's calibrated set tabulated for the vehicle's tire, and the ROM
// driven on that table. On soft soil the vehicle gains less speed than on rigid ground (the soil's
// compaction resistance and its limited traction), and the job's run is the command's own.
TEST_CASE("campaign: a vehicle drives on each entry's calibrated soil through its wheel table", "[cli][campaign]") {
  const ScratchDir scratch("campaign_vehicles");
  const std::string dir = scratch.str();
  write(dir + "/tire.json", R"({"radius": 0.4699, "width": 0.254, "mass": 600, "angular_velocity": 4.0})");
  write(dir + "/accel.json",
        R"({"type": "straight_acceleration", "throttle": 0.5, "start_time": 0.5, "initial_speed": 2, "end_time": 3})");
  write(dir + "/spec.json", R"({"soils": [{"name": "sand", "scm": ")" + demo_data("truth.json") +
                                R"("}], "gravities": [9.81, 3.71], "wheels": [{"name": "tire", "wheel": "tire.json"}],
    "vehicles": [{"name": "hmmwv", "vehicle": "hmmwv", "maneuver": "accel.json", "wheel": "tire"}],
    "stages": ["bevameter", "calibrate", "wheel_table", "rom"],
    "options": {"bevameter": {"no-plots": true}, "calibrate": {"min-ess": 200, "no-plots": true},
                "wheel_table": {"loads": [3000, 7000], "slips": [0, 0.2, 0.5], "slip-angles": [0, 0.2],
                                "duration": 1, "grid": 0.04},
                "rom": {"no-plots": true}}})");
  CliResult r = run_cli("campaign " + dir + "/spec.json --out " + dir + "/c", dir);
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(counts(r.out).jobs == 8);  // per gravity: bevameter, calibrate, wheel_table, rom
  const std::string report = read_file(dir + "/c/report.md");
  CHECK(report.find("## Vehicles on each entry's soil") != std::string::npos);
  CHECK(report.find("| sand_g3.71_hmmwv |") != std::string::npos);

  const fs::path table = job_dir(dir + "/c", "wheel_table", "sand_g9.81_tire");
  const fs::path rom = job_dir(dir + "/c", "rom", "sand_g9.81_hmmwv");
  REQUIRE(fs::exists(table / "table.h5"));
  REQUIRE(!rom.empty());
  REQUIRE(run_cli("rom --model 18dof --vehicle hmmwv --maneuver " + dir + "/accel.json --terrain-table " +
                      (table / "table.h5").string() + " --gravity 9.81 --no-plots --out " + dir + "/alone",
                  dir).exit_code == 0);
  CHECK(read_file((rom / "trajectory.csv").string()) == read_file(dir + "/alone/trajectory.csv"));
  REQUIRE(run_cli("rom --model 18dof --vehicle hmmwv --maneuver " + dir + "/accel.json --no-plots --out " + dir +
                      "/rigid",
                  dir).exit_code == 0);
  auto final_vx = [](const std::string& csv) -> double {
    const std::string text = read_file(csv);
    std::stringstream in(text);
    std::string line, last;
    std::getline(in, line);
    std::vector<std::string> names;
    std::stringstream hs(line);
    for (std::string n; std::getline(hs, n, ',');) names.push_back(n);
    while (std::getline(in, line))
      if (!line.empty()) last = line;
    std::stringstream ls(last);
    std::string cell;
    for (std::size_t i = 0; std::getline(ls, cell, ','); ++i)
      if (names[i] == "vx") return std::stod(cell);
    return NAN;
  };
  const double soft = final_vx((rom / "trajectory.csv").string()), rigid = final_vx(dir + "/rigid/trajectory.csv");
  INFO("final speed on the calibrated soil " << soft << " m/s, on rigid ground " << rigid << " m/s");
  CHECK(soft > 2.0);  // it still accelerates from its 2 m/s
  CHECK(soft < rigid - 0.05);
}
