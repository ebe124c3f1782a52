#include "apps/study_report.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "apps/campaign_db.hpp"
#include "apps/report_plots.hpp"
#include "apps/study_spec.hpp"
#include "apps/wheel_compare.hpp"
#include "core/atomic_file.hpp"

namespace terracal::app {
namespace fs = std::filesystem;
namespace {

using Columns = std::map<std::string, std::vector<double>>;
const char* kQuantities[3] = {"dbp_N", "torque_Nm", "sinkage_m"};

// One run with what its job left.
struct RunResult {
  const StudyRun* run = nullptr;
  JobRow row;
  Columns wheel;     // wheel.csv, empty unless done
  double wall = NAN;  // run.json's wall_seconds: the rig's own time, without start-up
};

std::vector<RunResult> collect(const std::string& dir, const StudySpec& spec, const std::vector<CampaignJob>& jobs,
                               const CampaignDb& db) {
  std::map<std::string, JobRow> rows;
  for (auto& r : db.rows()) rows[r.key] = r;
  std::vector<RunResult> out;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    RunResult r{&spec.runs[i], rows[jobs[i].key], {}, NAN};
    if (r.row.state == "done") {
      const fs::path folder = fs::path(dir) / jobs[i].dir;
      r.wheel = read_csv_columns((folder / "wheel.csv").string());
      try {
        std::ifstream in(folder / "run.json");
        r.wall = nlohmann::json::parse(in).value("wall_seconds", NAN);
      } catch (const std::exception&) {
      }
    }
    out.push_back(std::move(r));
  }
  return out;
}

// The largest of the three RMSEs (drawbar pull, torque, sinkage) of a against b, each in % of b's.
std::array<double, 4> errors(const Columns& a, const Columns& b) {
  std::array<double, 4> e{};
  e[3] = 0;
  for (int q = 0; q < 3; ++q) {
    const auto ia = a.find(kQuantities[q]), ib = b.find(kQuantities[q]);
    e[q] = ia == a.end() || ib == b.end() ? NAN : rmse_percent(ia->second, ib->second);
    e[3] = std::isfinite(e[q]) && std::isfinite(e[3]) ? std::max(e[3], e[q]) : NAN;
  }
  return e;
}

std::string jobs_table(const std::vector<RunResult>& rs) {
  std::string t = "| run | state | wall of the job [s] | ran on | error |\n|---|---|---|---|---|\n";
  for (const auto& r : rs)
    t += fmt::format("| {} | {} | {:.3g} | {} | {} |\n", r.run->label, r.row.state, r.row.wall_seconds, r.row.worker,
                     r.row.error);
  return t;
}

const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf"};

// Groups in first-seen order, the reference / base left out.
std::vector<std::string> groups_of(const std::vector<RunResult>& rs) {
  std::vector<std::string> g;
  for (const auto& r : rs)
    if (!r.run->reference && std::find(g.begin(), g.end(), r.run->group) == g.end()) g.push_back(r.run->group);
  return g;
}

std::string accuracy_cost(const std::string& dir, const std::vector<RunResult>& rs) {
  const RunResult& ref = rs.front();
  std::string csv = "knob,value,label,wall_s,dbp_err_pct,torque_err_pct,sinkage_err_pct,max_err_pct,pareto\n";
  std::string md = fmt::format(
      "Each knob from coarse to fine with the others at their finest; the reference runs every knob at its finest "
      "({:.3g} s wall). Error: RMSE over the slips against the reference, in % of the reference's largest value. "
      "Wall: the wheel runs' own time (run.json): without start-up and, for CRM, without settling the bed.\n\n| knob | value | wall [s] | drawbar pull | torque | sinkage | on the "
      "Pareto front |\n|---|---|---|---|---|---|---|\n",
      ref.wall);
  std::vector<std::array<double, 4>> err(rs.size());
  for (std::size_t i = 1; i < rs.size(); ++i) err[i] = errors(rs[i].wheel, ref.wheel);
  // Pareto: no other run is at least as fast and at least as accurate, and better in one.
  auto pareto = [&](std::size_t i) {
    if (!std::isfinite(err[i][3]) || !std::isfinite(rs[i].wall)) return false;
    for (std::size_t j = 1; j < rs.size(); ++j)
      if (j != i && std::isfinite(err[j][3]) && rs[j].wall <= rs[i].wall && err[j][3] <= err[i][3] &&
          (rs[j].wall < rs[i].wall || err[j][3] < err[i][3]))
        return false;
    return true;
  };
  std::map<std::string, std::string> data;
  std::string front;
  for (std::size_t i = 1; i < rs.size(); ++i) {
    const auto& r = rs[i];
    const bool p = pareto(i);
    md += fmt::format("| {} | {} | {:.3g} | {} | {} | {} | {} |\n", r.run->group, r.run->value, r.wall,
                      percent_text(err[i][0]), percent_text(err[i][1]), percent_text(err[i][2]), p ? "yes" : "");
    csv += fmt::format("{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{}\n", r.run->group, r.run->value, r.run->label,
                       r.wall, err[i][0], err[i][1], err[i][2], err[i][3], p ? 1 : 0);
    if (std::isfinite(err[i][3]) && err[i][3] > 0 && std::isfinite(r.wall) && r.wall > 0) {
      data[r.run->group] += fmt::format("{} {} {}\n", r.wall, err[i][3], r.run->value);
      if (p) front += fmt::format("{} {}\n", r.wall, err[i][3]);
    }
  }
  write_text_atomically(dir + "/accuracy_cost.csv", csv);
  // The front sorted by wall time, drawn as a step line.
  std::vector<std::pair<double, double>> f;
  for (std::size_t i = 1; i < rs.size(); ++i)
    if (pareto(i) && err[i][3] > 0) f.push_back({rs[i].wall, err[i][3]});
  std::sort(f.begin(), f.end());
  front.clear();
  for (auto [w, e] : f) front += fmt::format("{} {}\n", w, e);
  std::vector<std::pair<std::string, std::string>> files = {{"front.dat", front.empty() ? "nan nan\n" : front}};
  std::string s = fmt::format(
      "set terminal pngcairo noenhanced size 900,620 font 'Sans,11'\nset output 'accuracy_cost.png'\nset logscale "
      "xy\nset grid\nset key outside right\nset xlabel 'wall time [s]'\nset ylabel 'largest error against the "
      "reference [%]'\nset title 'accuracy against cost'\nset arrow from {0},graph 0 to {0},graph 1 nohead dt 2 lc "
      "rgb 'gray'\nplot 'front.dat' using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', ",
      ref.wall > 0 ? ref.wall : 1);
  int c = 0;
  for (const auto& [g, d] : data) {
    files.push_back({g + ".dat", d});
    s += fmt::format("'{0}.dat' using 1:2 with linespoints pt 7 ps 1.3 lc rgb '{1}' title '{0}', '{0}.dat' using "
                     "1:2:(sprintf('%g', $3)) with labels offset 0.8,0.6 left tc rgb '{1}' notitle, ",
                     g, kColours[c++ % 8]);
  }
  s.resize(s.size() - 2);
  draw_plot(dir, "accuracy_cost.png", s + "\n", files);
  return md + "\nThe dashed line: the reference's wall time.\n\n![accuracy against cost](accuracy_cost.png)\n\nData: "
              "`accuracy_cost.csv`.\n";
}

double mean_of(const Columns& c, const char* key) {
  const auto it = c.find(key);
  if (it == c.end() || it->second.empty()) return NAN;
  double s = 0;
  for (double v : it->second) s += v;
  return s / double(it->second.size());
}

std::string stability(const std::string& dir, const StudySpec& spec, const std::vector<RunResult>& rs) {
  std::string csv = "sweep,value,label,verdict,dbp_over_weight,sinkage_m,wall_s\n";
  std::string md =
      "Each sweep changes one setting of the base; a run is stable when it ends with finite, bounded, steady results "
      "(docs/study.md). Drawbar pull over weight and sinkage: means over the run's slips.\n\n| sweep | value | "
      "verdict | DBP / weight | sinkage [m] | wall [s] |\n|---|---|---|---|---|---|\n";
  std::map<std::string, std::pair<std::string, std::string>> data;  // group -> (stable, unstable) points
  int unstable = 0;
  for (const auto& r : rs) {
    const double radius = r.run->wheel.value("radius", 0.0);
    // The weight under this run's gravity: the sweep's own, or the base's (Earth unless set).
    double g = 9.81;
    if (r.run->options.contains("gravity")) g = std::fabs(r.run->options["gravity"][2].get<double>());
    if (r.run->soil.contains("gravity")) g = std::fabs(r.run->soil["gravity"][2].get<double>());
    const double weight = r.run->wheel.value("mass", 0.0) * g;
    const std::string v = stability_verdict(r.row.state, r.row.error, r.wheel, radius, weight);
    const double dbpw = mean_of(r.wheel, "dbp_N") / weight, z = mean_of(r.wheel, "sinkage_m");
    unstable += v != kStable;
    md += fmt::format("| {} | {} | {} | {:.3g} | {:.3g} | {:.3g} |\n", r.run->group, r.run->reference ? "" :
                      fmt::format("{}", r.run->value), v, dbpw, z, r.wall);
    csv += fmt::format("{},{},{},\"{}\",{:.6g},{:.6g},{:.6g}\n", r.run->group, r.run->value, r.run->label, v, dbpw, z,
                       r.wall);
    if (r.run->reference || r.run->group == "standstill") continue;
    auto& [good, bad] = data[r.run->group];
    (v == kStable ? good : bad) += fmt::format("{} {}\n", r.run->value, v == kStable && std::isfinite(dbpw) ? dbpw : 0);
  }
  write_text_atomically(dir + "/stability.csv", csv);
  const auto groups = groups_of(rs);
  std::vector<std::pair<std::string, std::string>> files;
  int panels = 0;
  std::string body;
  for (const auto& g : groups) {
    if (!data.count(g)) continue;
    ++panels;
    files.push_back({g + "_ok.dat", data[g].first.empty() ? "nan nan\n" : data[g].first});
    files.push_back({g + "_bad.dat", data[g].second.empty() ? "nan nan\n" : data[g].second});
    bool positive = true;
    double lo = INFINITY, hi = 0;
    for (const auto& r : rs)
      if (r.run->group == g) {
        positive = positive && r.run->value > 0;
        lo = std::min(lo, r.run->value);
        hi = std::max(hi, r.run->value);
      }
    body += fmt::format("{}set title '{}'\nset xlabel '{}'\nplot '{}_ok.dat' using 1:2 with points pt 7 ps 1.6 lc rgb "
                        "'#2ca02c' title 'stable', '{}_bad.dat' using 1:2 with points pt 2 ps 2.5 lw 3 lc rgb '#d62728' "
                        "title 'not stable'\n",
                        positive && hi / lo >= 20 ? "set logscale x\n" : "unset logscale x\n", g, g, g, g);
  }
  if (panels > 0) {
    const int cols = std::min(panels, 3), rows = (panels + cols - 1) / cols;
    const std::string s = fmt::format(
        "set terminal pngcairo noenhanced size {},{} font 'Sans,11'\nset output 'stability.png'\nset multiplot layout "
        "{},{} title '{}: where the solver stays stable'\nset grid\nset key below\nset format x '%g'\nset ylabel 'drawbar pull / "
        "weight'\n{}unset multiplot\n",
        480 * cols, 380 * rows, rows, cols, soil_model_name(spec.solver), body);
    draw_plot(dir, "stability.png", s, files);
  }
  return fmt::format("**{} of {} runs not stable.**\n\n", unstable, rs.size()) + md +
         "\n![stability map](stability.png)\n\nData: `stability.csv`.\n";
}

std::string effects(const std::string& dir, const std::vector<RunResult>& rs) {
  const RunResult& base = rs.front();
  std::string csv = "variant,options,wall_s,wall_over_base,dbp_change_pct,torque_change_pct,sinkage_change_pct\n";
  std::string md = fmt::format(
      "Each variant against the base settings ({:.3g} s wall): its cost and how far it moves the results (RMSE over "
      "the slips, in % of the base's largest value).\n\n| variant | options | wall [s] | wall / base | drawbar pull "
      "| torque | sinkage |\n|---|---|---|---|---|---|---|\n",
      base.wall);
  std::string dat;
  for (std::size_t i = 1; i < rs.size(); ++i) {
    const auto& r = rs[i];
    const auto e = errors(r.wheel, base.wheel);
    nlohmann::ordered_json own = nlohmann::ordered_json::object();
    for (const auto& [k, v] : r.run->options.items())
      if (!base.run->options.contains(k) || base.run->options[k] != v) own[k] = v;
    md += fmt::format("| {} | `{}` | {:.3g} | {:.3g} | {} | {} | {} |\n", r.run->label, own.dump(), r.wall,
                      r.wall / base.wall, percent_text(e[0]), percent_text(e[1]), percent_text(e[2]));
    csv += fmt::format("{},\"{}\",{:.6g},{:.6g},{:.6g},{:.6g},{:.6g}\n", r.run->label, own.dump(), r.wall,
                       r.wall / base.wall, e[0], e[1], e[2]);
    dat += fmt::format("\"{}\" {} {}\n", r.run->label, r.wall / base.wall, std::isfinite(e[3]) ? e[3] : 0);
  }
  write_text_atomically(dir + "/effects.csv", csv);
  const std::string s =
      "set terminal pngcairo noenhanced size 1100,420 font 'Sans,11'\nset output 'effects.png'\nset multiplot layout "
      "1,2\nset style fill solid 0.7\nset boxwidth 0.6\nset grid y\nset xtics rotate by -30\nset yrange [0:*]\nset "
      "title 'cost: wall time over the base'\nplot 'effects.dat' using 0:2:xtic(1) with boxes lc rgb '#1f77b4' "
      "notitle, 1 with lines dt 2 lc rgb 'gray' notitle\nset title 'change of the results [%]'\nplot 'effects.dat' "
      "using 0:3:xtic(1) with boxes lc rgb '#d62728' notitle\nunset multiplot\n";
  draw_plot(dir, "effects.png", s, {{"effects.dat", dat}});
  return md + "\n![effects: cost and change](effects.png)\n\nData: `effects.csv`.\n";
}

}  // namespace

std::string stability_verdict(const std::string& state, const std::string& error,
                              const std::map<std::string, std::vector<double>>& wheel, double radius, double weight) {
  if (state == "failed") return "failed (" + error + ")";
  if (state != "done") return state;
  for (const char* q : kQuantities) {
    const auto it = wheel.find(q);
    if (it == wheel.end() || it->second.empty()) return "no results";
    for (double x : it->second)
      if (!std::isfinite(x)) return "non-finite";
  }
  for (double x : wheel.at("sinkage_m"))
    if (x > radius) return "blew up (sinkage past the radius)";
  for (double x : wheel.at("dbp_N"))
    if (std::fabs(x) > 5 * weight) return "blew up (drawbar pull above 5 x weight)";
  for (double x : wheel.at("torque_Nm"))
    if (std::fabs(x) > 5 * weight * radius) return "blew up (torque above 5 x weight x radius)";
  if (const auto it = wheel.find("dbp_sd_N"); it != wheel.end())
    for (double x : it->second)
      if (x > weight) return "unsteady (drawbar pull's sd above the weight)";
  return kStable;
}

void write_study_report(const std::string& dir, const StudySpec& spec, const std::vector<CampaignJob>& jobs,
                        const CampaignDb& db) {
  const std::vector<RunResult> rs = collect(dir, spec, jobs, db);
  std::string md = fmt::format("# Study {}: {}\n\nSpec: {} (as run: `spec.json`). Single-wheel runs (`terracal wheel "
                               "--terrain {}`), each a job of a campaign in this folder (`terracal campaign --status` "
                               "on it lists them).\n\n",
                               study_kind_name(spec.kind), soil_model_name(spec.solver),
                               fs::path(spec.source).filename().string(), soil_model_name(spec.solver));
  const bool have_first = rs.front().row.state == "done";
  if (spec.kind == StudyKind::kStability)
    md += stability(dir, spec, rs);
  else if (!have_first)
    md += fmt::format("**The {} run did not finish ({}): nothing to compare with.**\n",
                      spec.kind == StudyKind::kEffects ? "base" : "reference", rs.front().row.error);
  else
    md += spec.kind == StudyKind::kAccuracyCost ? accuracy_cost(dir, rs) : effects(dir, rs);
  md += "\n## Jobs\n\n" + jobs_table(rs);
  write_text_atomically(dir + "/report.md", md);
}

}  // namespace terracal::app
