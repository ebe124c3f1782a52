#include "apps/campaign_report.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "apps/campaign_db.hpp"
#include "apps/campaign_plots.hpp"
#include "apps/campaign_spec.hpp"
#include "apps/wheel_compare.hpp"
#include "core/atomic_file.hpp"

namespace terracal::app {
namespace fs = std::filesystem;
namespace {

std::string percent(double v) { return std::isfinite(v) ? fmt::format("{:.1f} %", v) : "–"; }

// The vehicles on each entry's soil: speed at the end, distance, peak yaw rate, and the speed plot.
std::string rom_section(const std::string& dir, const std::vector<CampaignJob>& jobs,
                        std::map<std::string, JobRow>& row) {
  std::string md;
  std::vector<SpeedTrace> traces;
  for (const auto& j : jobs) {
    if (j.stage != "rom" || row[j.key].state != "done") continue;
    auto c = read_csv_columns((fs::path(dir) / j.dir / "trajectory.csv").string());
    const auto& t = c["time"];
    const auto& vx = c["vx"];
    const auto& x = c["x"];
    const auto& y = c["y"];
    if (t.empty() || vx.empty() || x.empty() || y.empty()) continue;
    double peak = 0;
    for (double r : c["yaw_rate"]) peak = std::max(peak, std::fabs(r));
    md += fmt::format("| {} | {:.3g} | {:.3g} | {:.3g} | {:.3g} | {:.3g} |\n", j.label, t.back(), vx.front(), vx.back(),
                      std::hypot(x.back() - x.front(), y.back() - y.front()), peak);
    traces.push_back({j.label, t, vx});
  }
  if (md.empty()) return "";
  plot_rom_speeds(dir, traces);
  return "\n## Vehicles on each entry's soil\n\nThe ROM on the wheel table of the entry's calibrated set "
         "(`terracal rom --terrain-table`).\n\n| entry | time [s] | vx at start [m/s] | vx at end [m/s] | distance "
         "[m] | peak yaw rate [rad/s] |\n|---|---|---|---|---|---|\n" +
         md + "\n![vehicle speed per entry](rom_speed.png)\n";
}

}  // namespace

void write_campaign_report(const std::string& dir, const CampaignSpec& spec, const std::vector<CampaignJob>& jobs,
                           const CampaignDb& db) {
  std::map<std::string, JobRow> row;
  for (auto& r : db.rows()) row[r.key] = r;
  int done = 0, failed = 0;
  std::map<std::string, std::pair<int, double>> per_stage;
  std::string table = "| stage | job | state | wall [s] | error |\n|---|---|---|---|---|\n";
  for (const auto& j : jobs) {
    const JobRow& r = row[j.key];
    done += r.state == "done";
    failed += r.state == "failed";
    if (r.state == "done") {
      per_stage[j.stage].first += 1;
      per_stage[j.stage].second += r.wall_seconds;
    }
    table += fmt::format("| {} | {} | {} | {:.3g} | {} |\n", j.stage, j.label, r.state, r.wall_seconds, r.error);
  }
  std::string md = fmt::format("# Campaign {}\n\n{} soils × {} gravities × {} wheels{}; stages {}. {} of {} jobs "
                               "done, {} failed.\n\n",
                               spec.name, spec.soils.size(), spec.gravities.size(), spec.wheels.size(),
                               spec.vehicles.empty() ? "" : fmt::format(" × {} vehicles", spec.vehicles.size()),
                               fmt::join(spec.stages, ", "), done, jobs.size(), failed);
  md += "## Wall time per stage\n\n| stage | jobs done | total [s] | per job [s] |\n|---|---|---|---|\n";
  std::vector<std::pair<std::string, double>> stage_wall;
  for (const auto& st : kCampaignStages)
    if (per_stage.count(st)) {
      md += fmt::format("| {} | {} | {:.3g} | {:.3g} |\n", st, per_stage[st].first, per_stage[st].second,
                        per_stage[st].second / per_stage[st].first);
      stage_wall.push_back({st, per_stage[st].second});
    }
  plot_stage_wall(dir, stage_wall);
  if (!stage_wall.empty()) md += "\n![wall time per stage](stage_wall.png)\n";

  // Calibrated parameters: median and 90 % interval per soil and gravity.
  std::string params;
  std::vector<std::string> names;
  std::map<std::string, std::vector<ParameterBand>> bands;
  for (const auto& j : jobs) {
    if (j.stage != "calibrate" || row[j.key].state != "done") continue;
    std::ifstream in(fs::path(dir) / j.dir / "scm_params.json");
    nlohmann::ordered_json p;
    try {
      in >> p;
    } catch (const std::exception&) {
      continue;
    }
    const auto& post = p.value("Posterior", nlohmann::ordered_json::object());
    if (names.empty())
      for (const auto& [k, v] : post.items())
        if (v.is_object() && v.contains("q50") && k.rfind("sigma2", 0) != 0) names.push_back(k);
    params += "| " + j.label;
    // The job's soil and gravity from its group (soil-major, as campaign_jobs makes them).
    const std::size_t ng = spec.gravities.size();
    const std::string soil = spec.soils[static_cast<std::size_t>(j.group) / ng].name;
    const double g = spec.gravities[static_cast<std::size_t>(j.group) % ng];
    for (const auto& n : names)
      if (post.contains(n))
        bands[n].push_back({soil, g, post[n].value("q05", NAN), post[n].value("q50", NAN), post[n].value("q95", NAN)});
    for (const auto& n : names)
      params += post.contains(n) ? fmt::format(" | {:.4g} ({:.3g} – {:.3g})", post[n].value("q50", NAN),
                                               post[n].value("q05", NAN), post[n].value("q95", NAN))
                                 : " | –";
    params += " |\n";
  }
  if (!params.empty()) {
    md += "\n## Calibrated SCM parameters: median (90 % interval)\n\n| soil, gravity |";
    for (const auto& n : names) md += " " + n + " |";
    md += "\n|---|";
    for (std::size_t i = 0; i < names.size(); ++i) md += "---|";
    md += "\n" + params;
    plot_parameter_bands(dir, names, bands);
    md += "\n![calibrated parameters against gravity](parameters.png)\n";
  }

  // The calibrated set's wheel against the reference soil's, per entry.
  std::string wheel;
  std::vector<WheelErrors> errors;
  for (const auto& j : jobs) {
    if (j.stage != "wheel" || row[j.key].state != "done") continue;
    const auto ref = std::find_if(jobs.begin(), jobs.end(),
                                  [&](const CampaignJob& r) { return r.stage == "wheel_reference" && r.label == j.label; });
    if (ref == jobs.end() || row[ref->key].state != "done") continue;
    auto a = read_csv_columns((fs::path(dir) / j.dir / "wheel.csv").string());
    auto b = read_csv_columns((fs::path(dir) / ref->dir / "wheel.csv").string());
    const WheelErrors e{j.label, rmse_percent(a["dbp_N"], b["dbp_N"]), rmse_percent(a["torque_Nm"], b["torque_Nm"]),
                        rmse_percent(a["sinkage_m"], b["sinkage_m"])};
    wheel += fmt::format("| {} | {} | {} | {} |\n", j.label, percent(e.dbp), percent(e.torque), percent(e.sinkage));
    errors.push_back(e);
  }
  plot_wheel_errors(dir, errors);
  if (!wheel.empty())
    md += "\n## Single wheel: the calibrated set against the reference soil\n\nRMSE over the slips, in % of the "
          "reference's largest value.\n\n| entry | drawbar pull | torque | sinkage |\n|---|---|---|---|\n" +
          wheel + "\n![wheel errors per entry](wheel_errors.png)\n";
  md += rom_section(dir, jobs, row);
  md += "\n## Jobs\n\n" + table;
  write_text_atomically(dir + "/report.md", md);
}

}  // namespace terracal::app
