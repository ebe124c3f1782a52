#include "apps/study_report.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

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

bool wheel_study(const StudySpec& s) { return study_command(s) == "wheel"; }
bool plate_study(const StudySpec& s) { return study_command(s) == "bevameter"; }

// The bevameter's plate.csv as one column: each plate's loading curve (phase "load") sampled at
// kPlatePoints evenly spaced fractions of its sinkage span, plate after plate (every run of a study
// has the same plates and stroke, so the samples line up).
constexpr int kPlatePoints = 20;
Columns plate_columns(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // plate_radius_m,sinkage_m,force_N,phase
  std::map<double, std::vector<std::pair<double, double>>> curves;
  while (std::getline(in, line)) {
    std::stringstream ls(line);
    std::string r, z, f, phase;
    if (!std::getline(ls, r, ',') || !std::getline(ls, z, ',') || !std::getline(ls, f, ',')) continue;
    std::getline(ls, phase, ',');
    if (phase != "load") continue;
    curves[std::stod(r)].push_back({std::stod(z), std::stod(f)});
  }
  Columns c;
  auto& force = c["force_N"];
  for (const auto& [radius, pts] : curves) {
    if (pts.size() < 2) continue;
    const double z0 = pts.front().first, z1 = pts.back().first;
    std::size_t k = 1;
    for (int i = 1; i <= kPlatePoints; ++i) {
      const double z = z0 + (z1 - z0) * i / kPlatePoints;
      while (k + 1 < pts.size() && pts[k].first < z) ++k;
      const auto& [za, fa] = pts[k - 1];
      const auto& [zb, fb] = pts[k];
      force.push_back(zb > za ? fa + (fb - fa) * (z - za) / (zb - za) : fb);
    }
  }
  return c;
}

// A step sweep's run that ends more than this far (largest RMSE in % of the base's largest value)
// from the base run has drifted: the base's own step changes its results by far less.
constexpr double kDriftPercent = 25;

// What runs are compared on: the wheel's steady means over the slips, or a vehicle's channels over time.
struct Quantity {
  std::string column, name, stem;  // in the run's CSV, in tables, in the study's CSV
};
std::vector<Quantity> quantities(const StudySpec& s) {
  if (plate_study(s)) return {{"force_N", "plate force", "force"}};
  if (wheel_study(s))
    return {{"dbp_N", "drawbar pull", "dbp"}, {"torque_Nm", "torque", "torque"}, {"sinkage_m", "sinkage", "sinkage"}};
  return {{"vx", "vx", "vx"}, {"yaw_rate", "yaw rate", "yaw_rate"}, {"ay", "ay", "ay"}, {"roll", "roll", "roll"}};
}

// One run with what its job left.
struct RunResult {
  const StudyRun* run = nullptr;
  JobRow row;
  Columns out;       // wheel.csv or trajectory.csv, empty unless done
  double wall = NAN;  // run.json's wall_seconds: the run's own time, without start-up
  double constraint_violation = NAN;  // the full vehicle's run.json: its largest constraint error
};

std::vector<RunResult> collect(const std::string& dir, const StudySpec& spec, const std::vector<CampaignJob>& jobs,
                               const CampaignDb& db) {
  std::map<std::string, JobRow> rows;
  for (auto& r : db.rows()) rows[r.key] = r;
  const std::string csv = plate_study(spec) ? "plate.csv" : wheel_study(spec) ? "wheel.csv" : "trajectory.csv";
  std::vector<RunResult> out;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    RunResult r{&spec.runs[i], rows[jobs[i].key], {}, NAN};
    if (r.row.state == "done") {
      const fs::path folder = fs::path(dir) / jobs[i].dir;
      r.out = plate_study(spec) ? plate_columns((folder / csv).string()) : read_csv_columns((folder / csv).string());
      try {
        std::ifstream in(folder / "run.json");
        const nlohmann::json j = nlohmann::json::parse(in);
        r.wall = j.value("wall_seconds", NAN);
        r.constraint_violation = j.value("max_constraint_violation", NAN);
      } catch (const std::exception&) {
      }
    }
    out.push_back(std::move(r));
  }
  return out;
}

// y(t) linearly interpolated at the times `at` (held at its ends); t increasing.
std::vector<double> resampled(const std::vector<double>& t, const std::vector<double>& y, const std::vector<double>& at) {
  std::vector<double> out;
  if (t.empty() || t.size() != y.size()) return std::vector<double>(at.size(), NAN);
  for (double x : at) {
    const auto hi = std::upper_bound(t.begin(), t.end(), x);
    if (hi == t.begin()) out.push_back(y.front());
    else if (hi == t.end()) out.push_back(y.back());
    else {
      const std::size_t k = static_cast<std::size_t>(hi - t.begin());
      const double w = (x - t[k - 1]) / (t[k] - t[k - 1]);
      out.push_back(y[k - 1] + w * (y[k] - y[k - 1]));
    }
  }
  return out;
}

// Each quantity's RMSE of a against b in % of b's largest value, then the largest of those that are
// finite (NaN when none is).
std::vector<double> errors(const StudySpec& s, const Columns& a, const Columns& b) {
  std::vector<double> e;
  double top = NAN;
  for (const auto& q : quantities(s)) {
    const auto ia = a.find(q.column), ib = b.find(q.column);
    if (ia == a.end() || ib == b.end()) {
      e.push_back(NAN);
    } else if (a.count("time") && b.count("time") && a.at("time") != b.at("time")) {
      // Runs whose steps do not divide the output interval sample other times: compare on b's.
      e.push_back(rmse_percent(resampled(a.at("time"), ia->second, b.at("time")), ib->second));
    } else {
      e.push_back(rmse_percent(ia->second, ib->second));
    }
    if (std::isfinite(e.back())) top = std::isfinite(top) ? std::max(top, e.back()) : e.back();
  }
  e.push_back(top);
  return e;
}

std::string error_headers(const StudySpec& s) {
  std::string h;
  for (const auto& q : quantities(s)) h += " " + q.name + " |";
  return h;
}
std::string error_cells(const std::vector<double>& e) {
  std::string c;
  for (std::size_t i = 0; i + 1 < e.size(); ++i) c += " " + percent_text(e[i]) + " |";
  return c;
}
std::string error_csv_header(const StudySpec& s, const char* suffix) {
  std::string h;
  for (const auto& q : quantities(s)) h += fmt::format(",{}_{}", q.stem, suffix);
  return h;
}
std::string error_csv(const std::vector<double>& e) {
  std::string c;
  for (std::size_t i = 0; i + 1 < e.size(); ++i) c += fmt::format(",{:.6g}", e[i]);
  return c;
}
std::string dashes(std::size_t n) {
  std::string d;
  for (std::size_t i = 0; i < n; ++i) d += "---|";
  return d;
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

std::string accuracy_cost(const std::string& dir, const StudySpec& spec, const std::vector<RunResult>& rs) {
  const RunResult& ref = rs.front();
  const std::size_t nq = quantities(spec).size();
  const bool own_reference = spec.merged.contains("reference");
  std::string csv = "knob,value,label,wall_s" + error_csv_header(spec, "err_pct") + ",max_err_pct,pareto\n";
  std::string md = fmt::format(
      "{} ({:.3g} s wall). Error: RMSE against the reference ({}), in % of the reference's largest value. Wall: the "
      "runs' own time (run.json): without start-up{}.\n\n| knob | value | wall [s] |{} on the Pareto front |\n|{}\n",
      own_reference ? fmt::format("The reference runs the base options with `{}`; each knob's runs set that knob "
                                  "alone over the base",
                                  spec.merged["reference"].dump())
                    : "Each knob from coarse to fine with the others at their finest; the reference runs every knob "
                      "at its finest",
      ref.wall,
      plate_study(spec)   ? "over each plate's loading curve, at 20 points of its stroke"
      : wheel_study(spec) ? "over the slips"
                          : "over the manoeuvre's samples",
      spec.solver != StudySolver::kCrm ? ""
      : plate_study(spec)              ? ", the bed's settling included (a bed per plate)"
                                       : " and without settling the bed",
      error_headers(spec), dashes(nq + 4));
  std::vector<std::vector<double>> err(rs.size());
  for (std::size_t i = 1; i < rs.size(); ++i) err[i] = errors(spec, rs[i].out, ref.out);
  // Pareto: no other run is at least as fast and at least as accurate, and better in one.
  auto pareto = [&](std::size_t i) {
    if (!std::isfinite(err[i][nq]) || !std::isfinite(rs[i].wall)) return false;
    for (std::size_t j = 1; j < rs.size(); ++j)
      if (j != i && std::isfinite(err[j][nq]) && rs[j].wall <= rs[i].wall && err[j][nq] <= err[i][nq] &&
          (rs[j].wall < rs[i].wall || err[j][nq] < err[i][nq]))
        return false;
    return true;
  };
  std::map<std::string, std::string> data;
  std::vector<std::pair<double, double>> front;
  for (std::size_t i = 1; i < rs.size(); ++i) {
    const auto& r = rs[i];
    const bool p = pareto(i);
    md += fmt::format("| {} | {} | {:.3g} |{} {} |\n", r.run->group, r.run->value_text, r.wall, error_cells(err[i]),
                      p ? "yes" : "");
    csv += fmt::format("{},{},{},{:.6g}{},{:.6g},{}\n", r.run->group, r.run->value_text, r.run->label, r.wall,
                       error_csv(err[i]), err[i][nq], p ? 1 : 0);
    if (std::isfinite(err[i][nq]) && err[i][nq] > 0 && std::isfinite(r.wall) && r.wall > 0) {
      data[r.run->group] += fmt::format("{} {} \"{}\"\n", r.wall, err[i][nq], r.run->value_text);
      if (p) front.push_back({r.wall, err[i][nq]});
    }
  }
  write_text_atomically(dir + "/accuracy_cost.csv", csv);
  std::sort(front.begin(), front.end());
  std::string f;
  for (auto [w, e] : front) f += fmt::format("{} {}\n", w, e);
  std::vector<std::pair<std::string, std::string>> files = {{"front.dat", f.empty() ? "nan nan\n" : f}};
  std::string s = fmt::format(
      "set terminal pngcairo noenhanced size 900,620 font 'Sans,11'\nset output 'accuracy_cost.png'\nset logscale "
      "xy\nset grid\nset key outside right\nset xlabel 'wall time [s]'\nset ylabel 'largest error against the "
      "reference [%]'\nset title '{}: accuracy against cost'\nset arrow from {},graph 0 to {},graph 1 nohead dt 2 lc "
      "rgb 'gray'\nplot 'front.dat' using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', ",
      study_solver_name(spec.solver), ref.wall > 0 ? ref.wall : 1, ref.wall > 0 ? ref.wall : 1);
  int c = 0;
  for (const auto& [g, d] : data) {
    files.push_back({g + ".dat", d});
    s += fmt::format("'{0}.dat' using 1:2 with linespoints pt 7 ps 1.3 lc rgb '{1}' title '{0}', '{0}.dat' using "
                     "1:2:3 with labels offset 0.8,0.6 left tc rgb '{1}' notitle, ",
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

double peak_of(const Columns& c, const char* key) {
  const auto it = c.find(key);
  if (it == c.end() || it->second.empty()) return NAN;
  double m = 0;
  for (double v : it->second) m = std::max(m, std::fabs(v));
  return m;
}

// A run's verdict and the two figures its row shows (the first is the plot's y).
struct Judged {
  std::string verdict;
  double a = NAN, b = NAN;
};

Judged judge(const StudySpec& spec, const RunResult& r) {
  if (!wheel_study(spec))
    return {vehicle_verdict(r.row.state, r.row.error, r.out, r.constraint_violation), peak_of(r.out, "yaw_rate"),
            r.out.count("vx") && !r.out.at("vx").empty() ? r.out.at("vx").back() : NAN};
  const auto& w = r.run->scene["wheel"];
  // The weight under this run's gravity: the sweep's own, or the base's (Earth unless set).
  double g = 9.81;
  if (r.run->options.contains("gravity")) g = std::fabs(r.run->options["gravity"][2].get<double>());
  if (r.run->scene.contains("soil") && r.run->scene["soil"].contains("gravity"))
    g = std::fabs(r.run->scene["soil"]["gravity"][2].get<double>());
  const double weight = w.value("mass", 0.0) * g;
  return {stability_verdict(r.row.state, r.row.error, r.out, w.value("radius", 0.0), weight),
          mean_of(r.out, "dbp_N") / weight, mean_of(r.out, "sinkage_m")};
}

std::string stability(const std::string& dir, const StudySpec& spec, const std::vector<RunResult>& rs) {
  const bool wheel = wheel_study(spec);
  const char* ya = wheel ? "DBP / weight" : "peak yaw rate [rad/s]";
  const char* yb = wheel ? "sinkage [m]" : "final vx [m/s]";
  std::string csv = wheel ? "sweep,value,label,verdict,dbp_over_weight,sinkage_m,wall_s\n"
                          : "sweep,value,label,verdict,peak_yaw_rate,final_vx,wall_s\n";
  std::string md = fmt::format(
      "Each sweep changes one setting of the base; a run is stable when it ends with finite, bounded{} results "
      "(docs/study.md).{}\n\n| sweep | value | verdict | {} | {} | wall [s] |\n|---|---|---|---|---|---|\n",
      wheel ? ", steady" : "", wheel ? " Drawbar pull over weight and sinkage: means over the run's slips." : "", ya, yb);
  std::map<std::string, std::pair<std::string, std::string>> data;  // group -> (stable, unstable) points
  int unstable = 0;
  for (const auto& r : rs) {
    Judged j = judge(spec, r);
    // A step is a numerical setting: a run that ends far from the base run has diverged even when
    // nothing blew up (a ROM that loses its speed at too long a step).
    if (j.verdict == kStable && r.run->group == "step" && rs.front().row.state == "done") {
      const double drift = errors(spec, r.out, rs.front().out).back();
      if (drift > kDriftPercent) j.verdict = fmt::format("drifted ({:.0f} % from the base run)", drift);
    }
    unstable += j.verdict != kStable;
    md += fmt::format("| {} | {} | {} | {:.3g} | {:.3g} | {:.3g} |\n", r.run->group, r.run->value_text, j.verdict, j.a,
                      j.b, r.wall);
    csv += fmt::format("{},{},{},\"{}\",{:.6g},{:.6g},{:.6g}\n", r.run->group, r.run->value_text, r.run->label,
                       j.verdict, j.a, j.b, r.wall);
    if (r.run->reference || r.run->group == "standstill") continue;
    auto& [good, bad] = data[r.run->group];
    (j.verdict == kStable ? good : bad) +=
        fmt::format("{} {}\n", r.run->value, j.verdict == kStable && std::isfinite(j.a) ? j.a : 0);
  }
  write_text_atomically(dir + "/stability.csv", csv);
  std::vector<std::pair<std::string, std::string>> files;
  int panels = 0;
  std::string body;
  for (const auto& g : groups_of(rs)) {
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
        "{},{} title '{}: where the solver stays stable'\nset grid\nset key below\nset format x '%g'\nset ylabel "
        "'{}'\n{}unset multiplot\n",
        480 * cols, 380 * rows, rows, cols, study_solver_name(spec.solver), ya, body);
    draw_plot(dir, "stability.png", s, files);
  }
  return fmt::format("**{} of {} runs not stable.**\n\n", unstable, rs.size()) + md +
         "\n![stability map](stability.png)\n\nData: `stability.csv`.\n";
}

std::string effects(const std::string& dir, const StudySpec& spec, const std::vector<RunResult>& rs) {
  const RunResult& base = rs.front();
  const std::size_t nq = quantities(spec).size();
  std::string csv = "variant,changes,wall_s,wall_over_base" + error_csv_header(spec, "change_pct") + "\n";
  std::string md = fmt::format(
      "Each variant against the base settings ({:.3g} s wall): its cost and how far it moves the results (RMSE, in "
      "% of the base's largest value).\n\n| variant | changes | wall [s] | wall / base |{}\n|{}\n",
      base.wall, error_headers(spec), dashes(nq + 4));
  std::string dat;
  for (std::size_t i = 1; i < rs.size(); ++i) {
    const auto& r = rs[i];
    const auto e = errors(spec, r.out, base.out);
    nlohmann::ordered_json own = nlohmann::ordered_json::object();
    for (const auto& [k, v] : r.run->options.items())
      if (!base.run->options.contains(k) || base.run->options[k] != v) own[k] = v;
    if (r.run->scene.contains("vehicle") && r.run->scene["vehicle"].is_object() &&
        r.run->scene["vehicle"] != base.run->scene["vehicle"])
      own["vehicle effects"] = r.run->scene["vehicle"].value("effects", nlohmann::ordered_json::array());
    md += fmt::format("| {} | `{}` | {:.3g} | {:.3g} |{}\n", r.run->label, own.dump(), r.wall, r.wall / base.wall,
                      error_cells(e));
    std::string quoted = own.dump();
    for (std::size_t k = 0; (k = quoted.find('"', k)) != std::string::npos; k += 2) quoted.insert(k, "\"");
    csv += fmt::format("{},\"{}\",{:.6g},{:.6g}{}\n", r.run->label, quoted, r.wall, r.wall / base.wall, error_csv(e));
    dat += fmt::format("\"{}\" {} {}\n", r.run->label, r.wall / base.wall, std::isfinite(e[nq]) ? e[nq] : 0);
  }
  write_text_atomically(dir + "/effects.csv", csv);
  const std::string s =
      "set terminal pngcairo noenhanced size 1100,420 font 'Sans,11'\nset output 'effects.png'\nset multiplot layout "
      "1,2\nset style fill solid 0.7\nset boxwidth 0.6\nset grid y\nset xtics rotate by -30\nset yrange [0:*]\nset "
      "title 'cost: wall time over the base'\nplot 'effects.dat' using 0:2:xtic(1) with boxes lc rgb '#1f77b4' "
      "notitle, 1 with lines dt 2 lc rgb 'gray' notitle\nset title 'largest change of the results [%]'\nplot "
      "'effects.dat' using 0:3:xtic(1) with boxes lc rgb '#d62728' notitle\nunset multiplot\n";
  draw_plot(dir, "effects.png", s, {{"effects.dat", dat}});
  return md + "\n![effects: cost and change](effects.png)\n\nData: `effects.csv`.\n";
}

}  // namespace

std::string stability_verdict(const std::string& state, const std::string& error,
                              const std::map<std::string, std::vector<double>>& wheel, double radius, double weight) {
  if (state == "failed") return "failed (" + error + ")";
  if (state != "done") return state;
  for (const char* q : {"dbp_N", "torque_Nm", "sinkage_m"}) {
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

std::string vehicle_verdict(const std::string& state, const std::string& error,
                            const std::map<std::string, std::vector<double>>& trajectory,
                            double max_constraint_violation) {
  if (state == "failed") return "failed (" + error + ")";
  if (state != "done") return state;
  for (const char* q : {"vx", "yaw_rate", "ay", "roll"}) {
    const auto it = trajectory.find(q);
    if (it == trajectory.end() || it->second.empty()) return "no results";
    for (double x : it->second)
      if (!std::isfinite(x)) return "non-finite";
  }
  for (double x : trajectory.at("vx"))
    if (std::fabs(x) > 100) return "blew up (|vx| above 100 m/s)";
  for (double x : trajectory.at("yaw_rate"))
    if (std::fabs(x) > 10) return "blew up (|yaw rate| above 10 rad/s)";
  for (double x : trajectory.at("ay"))
    if (std::fabs(x) > 100) return "blew up (|ay| above 100 m/s^2)";
  for (double x : trajectory.at("roll"))
    if (std::fabs(x) > 1) return "rolled over (|roll| above 1 rad)";
  if (max_constraint_violation > kConstraintDrift)
    return fmt::format("constraint drift (joints off by up to {:.3g})", max_constraint_violation);
  return kStable;
}

void write_study_report(const std::string& dir, const StudySpec& spec, const std::vector<CampaignJob>& jobs,
                        const CampaignDb& db) {
  const std::vector<RunResult> rs = collect(dir, spec, jobs, db);
  const std::string command = study_command(spec);
  std::string md = fmt::format("# Study {}: {}\n\nSpec: {} (as run: `spec.json`). Runs of `terracal {}`, each a job "
                               "of a campaign in this folder (`terracal campaign --status` on it lists them).\n\n",
                               study_kind_name(spec.kind), study_solver_name(spec.solver),
                               fs::path(spec.source).filename().string(), command);
  if (spec.kind == StudyKind::kStability)
    md += stability(dir, spec, rs);
  else if (rs.front().row.state != "done")
    md += fmt::format("**The {} run did not finish ({}): nothing to compare with.**\n",
                      spec.kind == StudyKind::kEffects ? "base" : "reference", rs.front().row.error);
  else
    md += spec.kind == StudyKind::kAccuracyCost ? accuracy_cost(dir, spec, rs) : effects(dir, spec, rs);
  md += "\n## Jobs\n\n" + jobs_table(rs);
  write_text_atomically(dir + "/report.md", md);
}

}  // namespace terracal::app
