#include "apps/campaign_plots.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include <fmt/format.h>

#include "apps/report_plots.hpp"

namespace terracal::app {
namespace {
const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf"};
}

void plot_parameter_bands(const std::string& dir, const std::vector<std::string>& names,
                          const std::map<std::string, std::vector<ParameterBand>>& bands) {
  if (names.empty()) return;
  std::vector<std::string> soils;
  std::set<double> gravities;
  for (const auto& [n, list] : bands)
    for (const auto& b : list) {
      if (std::find(soils.begin(), soils.end(), b.soil) == soils.end()) soils.push_back(b.soil);
      gravities.insert(b.gravity);
    }
  std::vector<std::pair<std::string, std::string>> files;
  const bool log_g = gravities.size() > 1 && *gravities.rbegin() / *gravities.begin() >= 3;
  const int cols = std::min<int>(static_cast<int>(names.size()), 4);
  const int rows = (static_cast<int>(names.size()) + cols - 1) / cols;
  std::string s = fmt::format(
      "set terminal pngcairo noenhanced size {},{} font 'Sans,10'\nset output 'parameters.png'\nset multiplot "
      "layout {},{} title 'calibrated SCM parameters: median and 90 % interval'\nset grid\nset key top right "
      "font ',8'\nset xlabel 'gravity [m/s^2]'\nset offsets graph 0.08, graph 0.08, 0, 0\n{}",
      380 * cols, 320 * rows, rows, cols, log_g ? "set logscale x\n" : "");
  for (std::size_t p = 0; p < names.size(); ++p) {
    s += fmt::format("set title '{}'\nplot ", names[p]);
    for (std::size_t k = 0; k < soils.size(); ++k) {
      std::string d;
      std::vector<ParameterBand> list;
      for (const auto& b : bands.at(names[p]))
        if (b.soil == soils[k]) list.push_back(b);
      std::sort(list.begin(), list.end(), [](const auto& a, const auto& b) { return a.gravity < b.gravity; });
      for (const auto& b : list) d += fmt::format("{} {} {} {}\n", b.gravity, b.q50, b.q05, b.q95);
      const std::string file = fmt::format("p{}_s{}.dat", p, k);
      files.push_back({file, d.empty() ? "nan nan nan nan\n" : d});
      s += fmt::format("'{}' using 1:2:3:4 with yerrorlines lw 2 pt 7 lc rgb '{}' title '{}', ", file,
                       kColours[k % 8], soils[k]);
    }
    s.resize(s.size() - 2);
    s += "\n";
  }
  draw_plot(dir, "parameters.png", s + "unset multiplot\n", files);
}

void plot_wheel_errors(const std::string& dir, const std::vector<WheelErrors>& errors) {
  if (errors.empty()) return;
  std::string d;
  for (const auto& e : errors)
    d += fmt::format("\"{}\" {} {} {}\n", e.entry, std::isfinite(e.dbp) ? e.dbp : 0,
                     std::isfinite(e.torque) ? e.torque : 0, std::isfinite(e.sinkage) ? e.sinkage : 0);
  const std::string s = fmt::format(
      "set terminal pngcairo noenhanced size {},460 font 'Sans,10'\nset output 'wheel_errors.png'\nset title "
      "'single wheel: the calibrated set against the reference soil'\nset style data histogram\nset style "
      "histogram clustered gap 1\nset style fill solid 0.8\nset grid y\nset yrange [0:*]\nset ylabel 'RMSE over "
      "the slips [% of the reference largest]'\nset xtics rotate by -25\nplot 'e.dat' using 2:xtic(1) title "
      "'drawbar pull' lc rgb '#1f77b4', '' using 3 title 'torque' lc rgb '#d62728', '' using 4 title 'sinkage' lc "
      "rgb '#2ca02c'\n",
      std::max<std::size_t>(700, 120 * errors.size()));
  draw_plot(dir, "wheel_errors.png", s, {{"e.dat", d}});
}

void plot_rom_speeds(const std::string& dir, const std::vector<SpeedTrace>& traces) {
  if (traces.empty()) return;
  std::vector<std::pair<std::string, std::string>> files;
  std::string s =
      "set terminal pngcairo noenhanced size 800,460 font 'Sans,10'\nset output 'rom_speed.png'\nset title "
      "\"vehicles on each entry's soil (ROM on the wheel table)\"\nset grid\nset key outside right font ',8'\n"
      "set xlabel 'time [s]'\nset ylabel 'vx [m/s]'\nplot ";
  for (std::size_t i = 0; i < traces.size(); ++i) {
    std::string d;
    for (std::size_t k = 0; k < traces[i].t.size() && k < traces[i].vx.size(); ++k)
      d += fmt::format("{} {}\n", traces[i].t[k], traces[i].vx[k]);
    const std::string file = fmt::format("v{}.dat", i);
    files.push_back({file, d});
    s += fmt::format("{}'{}' using 1:2 with lines lw 2 lc rgb '{}' title '{}'", i ? ", " : "", file,
                     kColours[i % std::size(kColours)], traces[i].entry);
  }
  draw_plot(dir, "rom_speed.png", s + "\n", files);
}

void plot_stage_wall(const std::string& dir, const std::vector<std::pair<std::string, double>>& wall) {
  if (wall.empty()) return;
  std::string d;
  for (const auto& [stage, w] : wall) d += fmt::format("\"{}\" {}\n", stage, w);
  const std::string s =
      "set terminal pngcairo noenhanced size 700,400 font 'Sans,10'\nset output 'stage_wall.png'\nset title 'wall "
      "time per stage (jobs done)'\nset style fill solid 0.8\nset boxwidth 0.6\nset grid y\nset yrange [0:*]\nset "
      "ylabel 'wall [s]'\nplot 'w.dat' using 0:2:xtic(1) with boxes lc rgb '#1f77b4' notitle\n";
  draw_plot(dir, "stage_wall.png", s, {{"w.dat", d}});
}

}  // namespace terracal::app
