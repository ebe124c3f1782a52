// `terracal study`: the three studies on SCM and Wong-Reece at small settings, checked against what
// the physics says (errors shrink with resolution, a step past the contact's limit is caught, an
// effect that changes the model changes the result) and resumed without recomputing.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <map>
#include <regex>
#include <string>
#include <vector>

#include "apps/study_report.hpp"
#include "apps/wheel_compare.hpp"
#include "cli_runner.hpp"

using namespace terracal::test;
namespace fs = std::filesystem;

namespace {

// The study's CSV as rows keyed by its label column.
std::map<std::string, std::map<std::string, std::string>> rows_by_label(const std::string& csv, const char* label) {
  std::map<std::string, std::map<std::string, std::string>> out;
  std::stringstream in(read_file(csv));
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::stringstream hs(line);
  for (std::string n; std::getline(hs, n, ',');) names.push_back(n);
  while (std::getline(in, line)) {
    std::map<std::string, std::string> row;
    std::size_t c = 0;
    bool quoted = false;
    std::string cell;
    for (char ch : line + ",") {
      if (ch == '"') quoted = !quoted;
      else if (ch == ',' && !quoted) {
        if (c < names.size()) row[names[c++]] = cell;
        cell.clear();
      } else cell += ch;
    }
    out[row[label]] = row;
  }
  return out;
}

double num(const std::map<std::string, std::string>& row, const std::string& key) { return std::stod(row.at(key)); }

int runs_now(const std::string& out) {
  std::smatch m;
  return std::regex_search(out, m, std::regex(R"(\((\d+) run now\))")) ? std::stoi(m[1]) : -1;
}

}  // namespace

TEST_CASE("study accuracy-cost: SCM's grid and step errors shrink towards the finest setting; resumes",
          "[cli][study]") {
  const ScratchDir scratch("study_accuracy");
  const std::string dir = scratch.str();
  write(dir + "/spec.json", R"({"options": {"slips": [0.2, 0.5], "duration": 1},
    "knobs": {"grid": [0.04, 0.02, 0.01], "step": [0.004, 0.002, 0.001]}})");
  const std::string cmd = "study accuracy-cost --solver scm --spec " + dir + "/spec.json --out " + dir + "/s";
  CliResult r = run_cli(cmd, dir);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(runs_now(r.out) == 5);  // the reference (grid 0.01, step 0.001) and two coarser values per knob
  const auto rows = rows_by_label(dir + "/s/accuracy_cost.csv", "label");
  REQUIRE(rows.size() == 4);
  // Convergence with resolution: each coarser setting is further from the reference.
  CHECK(num(rows.at("grid_0.04"), "max_err_pct") > num(rows.at("grid_0.02"), "max_err_pct"));
  CHECK(num(rows.at("step_0.004"), "max_err_pct") > num(rows.at("step_0.002"), "max_err_pct"));
  CHECK(num(rows.at("grid_0.02"), "max_err_pct") > 0);
  // The step error is first order (semi-implicit Euler): halving the step about halves it.
  const double ratio = num(rows.at("step_0.004"), "dbp_err_pct") / num(rows.at("step_0.002"), "dbp_err_pct");
  CHECK(ratio > 1.5);
  CHECK(ratio < 4.0);
  const std::string report = read_file(dir + "/s/report.md");
  CHECK(report.find("| grid | 0.04 |") != std::string::npos);
  CHECK(fs::exists(dir + "/s/spec.json"));
  // Again: nothing reruns.
  r = run_cli(cmd, dir);
  CHECK(r.exit_code == 0);
  CHECK(runs_now(r.out) == 0);
}

// The bevameter rig: SCM plates at three grids against a fine one. A plate that does not slip sees
// Bekker's law on every node, so the grid's error is that of resolving the plate's round edge; it
// shrinks as the grid refines (results/bevameter_cost: 3.1 % at 4 cm down to 0.03 % at 2.5 mm).
TEST_CASE("study accuracy-cost on the bevameter: SCM's plate force converges with the grid", "[cli][study]") {
  const ScratchDir scratch("study_plate");
  const std::string dir = scratch.str();
  write(dir + "/spec.json", R"({"rig": "bevameter", "options": {"max-sinkage": 0.1},
    "knobs": {"grid": [0.04, 0.02, 0.01, 0.005]}})");
  CliResult r = run_cli("study accuracy-cost --solver scm --spec " + dir + "/spec.json --out " + dir + "/p", dir);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(runs_now(r.out) == 4);
  const auto rows = rows_by_label(dir + "/p/accuracy_cost.csv", "label");
  const double e4 = num(rows.at("grid_0.04"), "force_err_pct"), e2 = num(rows.at("grid_0.02"), "force_err_pct"),
               e1 = num(rows.at("grid_0.01"), "force_err_pct");
  INFO("plate force error: " << e4 << " %, " << e2 << " %, " << e1 << " % at grids 4, 2, 1 cm");
  CHECK(e4 > e2);
  CHECK(e2 > e1);
  CHECK(e4 < 10);
  CHECK(read_file(dir + "/p/report.md").find("each plate's loading curve") != std::string::npos);
}

TEST_CASE("study stability: a step past SCM's contact limit is caught and named, the others stay stable",
          "[cli][study]") {
  const ScratchDir scratch("study_stability");
  const std::string dir = scratch.str();
  write(dir + "/spec.json", R"({"options": {"slips": [0.3], "duration": 0.5},
    "sweeps": {"step": [0.001, 0.05], "gravity": [1.62], "stiffness": [0.01, 100], "slip": [-0.5, 0.95],
               "standstill": true}})");
  const CliResult r = run_cli("study stability --solver scm --spec " + dir + "/spec.json --out " + dir + "/s", dir);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);  // unstable runs are the study's findings
  const auto rows = rows_by_label(dir + "/s/stability.csv", "label");
  CHECK(rows.at("step_0.001").at("verdict") == "stable");
  CHECK_THAT(rows.at("step_0.05").at("verdict"),
             Catch::Contains("failed") && Catch::Contains("unstable for its contact"));
  for (const char* ok : {"base", "gravity_1.62", "stiffness_0.01", "stiffness_100", "slip_-0.5", "slip_0.95",
                         "standstill"})
    CHECK(rows.at(ok).at("verdict") == "stable");
  // Softer soil sinks deeper; a wheel at rest pulls nothing; skid pulls backwards.
  CHECK(num(rows.at("stiffness_0.01"), "sinkage_m") > 3 * num(rows.at("stiffness_100"), "sinkage_m"));
  CHECK(std::fabs(num(rows.at("standstill"), "dbp_over_weight")) < 1e-3);
  CHECK(num(rows.at("slip_-0.5"), "dbp_over_weight") < 0);
  CHECK(read_file(dir + "/s/report.md").find("1 of 9 runs not stable") != std::string::npos);
}

TEST_CASE("study stability: the verdicts on a run's results", "[study]") {
  using terracal::app::stability_verdict;
  const std::map<std::string, std::vector<double>> ok = {
      {"dbp_N", {300}}, {"torque_Nm", {200}}, {"sinkage_m", {0.03}}, {"dbp_sd_N", {5}}};
  CHECK(stability_verdict("done", "", ok, 0.47, 1059) == "stable");
  auto bad = ok;
  bad["torque_Nm"] = {NAN};
  CHECK(stability_verdict("done", "", bad, 0.47, 1059) == "non-finite");
  bad = ok;
  bad["sinkage_m"] = {0.5};
  CHECK_THAT(stability_verdict("done", "", bad, 0.47, 1059), Catch::Contains("blew up"));
  bad = ok;
  bad["dbp_N"] = {-6000};
  CHECK_THAT(stability_verdict("done", "", bad, 0.47, 1059), Catch::Contains("blew up"));
  bad = ok;
  bad["dbp_sd_N"] = {2000};
  CHECK_THAT(stability_verdict("done", "", bad, 0.47, 1059), Catch::Contains("unsteady"));
  CHECK_THAT(stability_verdict("failed", "exit 3: x", ok, 0.47, 1059), Catch::Contains("exit 3: x"));
  CHECK(stability_verdict("done", "", {}, 0.47, 1059) == "no results");
}

TEST_CASE("study effects: bulldozing moves SCM's sinkage, elastic unloading hardly moves a steady wheel",
          "[cli][study]") {
  const ScratchDir scratch("study_effects");
  const std::string dir = scratch.str();
  write(dir + "/spec.json", R"({"options": {"slips": [0.1, 0.5], "duration": 2}})");
  const CliResult r = run_cli("study effects --solver scm --spec " + dir + "/spec.json --out " + dir + "/s", dir);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto rows = rows_by_label(dir + "/s/effects.csv", "variant");
  REQUIRE(rows.size() == 4);
  CHECK(num(rows.at("bulldozing"), "sinkage_change_pct") > 5);
  // Unloading happens behind the contact only: a wheel at steady slip barely sees it.
  CHECK(num(rows.at("elastic_unloading"), "sinkage_change_pct") < 0.1);
  // Without damping the contact rings: the results move.
  CHECK(num(rows.at("none"), "dbp_change_pct") > 0.1);
}

TEST_CASE("study accuracy-cost: Wong-Reece converges with its quadrature tolerance", "[cli][study]") {
  const ScratchDir scratch("study_wong_reece");
  const std::string dir = scratch.str();
  const CliResult r = run_cli("study accuracy-cost --solver wong-reece --out " + dir + "/s", dir);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto rows = rows_by_label(dir + "/s/accuracy_cost.csv", "label");
  CHECK(num(rows.at("wong-reece-tolerance_0.001"), "max_err_pct") < 0.1);
  CHECK(num(rows.at("wong-reece-tolerance_1e-06"), "max_err_pct") < 1e-4);
  CHECK(num(rows.at("wong-reece-tolerance_0.001"), "max_err_pct") >=
        num(rows.at("wong-reece-tolerance_1e-06"), "max_err_pct"));
}

TEST_CASE("study: the ROM's half-implicit step converges at first order; a too long step is caught as a rollover",
          "[cli][study]") {
  const ScratchDir scratch("study_rom");
  const std::string dir = scratch.str();
  write(dir + "/spec.json", R"({"knobs": {"step": [0.002, 0.001],
    "24dof_cvodes": [{"integrator": "cvodes", "rtol": 1e-4}, {"integrator": "cvodes", "rtol": 1e-6}]},
    "sweeps": {"step": [0.001, 0.006, 0.01]}})");
  CliResult r = run_cli("study accuracy-cost --solver rom --spec " + dir + "/spec.json --out " + dir + "/a", dir);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto rows = rows_by_label(dir + "/a/accuracy_cost.csv", "label");
  // Against CVODES at rtol 1e-10 (the reference): halving the step halves the error.
  const double ratio = num(rows.at("step_0.002"), "yaw_rate_err_pct") / num(rows.at("step_0.001"), "yaw_rate_err_pct");
  CHECK(ratio > 1.8);
  CHECK(ratio < 2.2);
  CHECK(num(rows.at("step_0.001"), "yaw_rate_err_pct") < 0.1);
  // A knob whose values set several options (the integrator with its tolerance): CVODES's error falls
  // with its tolerance (0.041 % at 1e-4, 0.0066 % at 1e-6 in results/rom_accuracy_cost).
  const auto& loose = rows.at("24dof_cvodes_0.0001");
  CHECK(loose.at("value") == "0.0001");
  CHECK(num(rows.at("24dof_cvodes_1e-06"), "yaw_rate_err_pct") < num(loose, "yaw_rate_err_pct") / 3);
  // The 24-DOF model at a 10 ms step diverges into a rollover the rom command itself does not stop:
  // the study's verdict is what catches it.
  r = run_cli("study stability --solver rom --spec " + dir + "/spec.json --out " + dir + "/s", dir);
  REQUIRE(r.exit_code == 0);
  const auto st = rows_by_label(dir + "/s/stability.csv", "label");
  CHECK(st.at("step_0.001").at("verdict") == "stable");
  CHECK_THAT(st.at("step_0.01").at("verdict"), Catch::Contains("rolled over") || Catch::Contains("blew up"));
  // At 6 ms nothing blows up, but the vehicle loses its speed: far from the base run, which the
  // verdict says (its samples fall on other times than the base's and are interpolated).
  CHECK_THAT(st.at("step_0.006").at("verdict"), Catch::Contains("drifted"));
}

TEST_CASE("study stability: the verdicts on a vehicle's trajectory", "[study]") {
  using terracal::app::vehicle_verdict;
  const std::map<std::string, std::vector<double>> ok = {
      {"vx", {20, 19}}, {"yaw_rate", {0, 0.5}}, {"ay", {0, 8}}, {"roll", {0, 0.05}}};
  CHECK(vehicle_verdict("done", "", ok) == "stable");
  auto bad = ok;
  bad["roll"] = {0, 1.4};
  CHECK_THAT(vehicle_verdict("done", "", bad), Catch::Contains("rolled over"));
  bad = ok;
  bad["vx"] = {20, INFINITY};
  CHECK(vehicle_verdict("done", "", bad) == "non-finite");
  bad = ok;
  bad["yaw_rate"] = {0, 40};
  CHECK_THAT(vehicle_verdict("done", "", bad), Catch::Contains("blew up"));
  // The full vehicle's joints: a run that holds them to 1e-6 is sound, one that lets them drift is not.
  CHECK(vehicle_verdict("done", "", ok, 2e-6) == "stable");
  CHECK_THAT(vehicle_verdict("done", "", ok, 0.02), Catch::Contains("constraint drift"));
}
