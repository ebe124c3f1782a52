#include "apps/report_plots.hpp"

#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "bayes/forward_models.hpp"
#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "core/gnuplot.hpp"

namespace terracal::app {

namespace {
void render(const std::string& dir, const std::string& script, const std::string& what) {
  if (!gnuplot_available()) {
    spdlog::warn("gnuplot not found: {} not drawn", what);
    return;
  }
  try {
    run_gnuplot(script, dir);
  } catch (const RunError& e) {
    spdlog::warn("{} not drawn: {}", what, e.what());
  }
}
// Moves a drawn plot from the work folder to `dir` through the shared write path, then removes the
// work folder. A plot that was not drawn was already reported by render().
void publish(const std::string& work, const std::string& name, const std::string& dir) {
  try {
    if (std::filesystem::exists(work + "/" + name)) commit_file(work + "/" + name, dir + "/" + name);
  } catch (const RunError& e) {
    spdlog::warn("{} not written: {}", name, e.what());
  }
  std::error_code ec;
  std::filesystem::remove_all(work, ec);
}

const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
                          "#8c564b", "#e377c2", "#7f7f7f", "#17becf"};
}  // namespace

void draw_plot(const std::string& dir, const std::string& png, const std::string& script,
               const std::vector<std::pair<std::string, std::string>>& data) {
  const std::string work = dir + "/.plot_" + png;
  std::filesystem::create_directories(work);
  for (const auto& [name, content] : data) write_text_atomically(work + "/" + name, content);
  render(work, script, png);
  publish(work, png, dir);
}

void plot_bevameter(const std::string& dir, const BevameterCurves& c, const lowfi::ScmSoil* fit) {
  const std::string work = dir + "/.plot_bevameter";
  std::filesystem::create_directories(work);
  std::string plate, shear, plate_fit, shear_fit;
  std::set<double> radii, loads;
  for (const auto& r : c.plate) {
    plate += fmt::format("{} {} {}\n", r.radius, r.sinkage, r.force);
    radii.insert(r.radius);
  }
  for (const auto& r : c.shear) {
    shear += fmt::format("{} {} {}\n", r.normal_load, r.angle, r.torque);
    loads.insert(r.normal_load);
  }
  double z_max = 0, a_max = 0;
  for (const auto& r : c.plate) z_max = std::max(z_max, r.sinkage);
  for (const auto& r : c.shear) a_max = std::max(a_max, r.angle);
  if (fit) {
    for (double r : radii) {
      for (int i = 1; i <= 100; ++i) {
        const double z = z_max * i / 100;
        plate_fit += fmt::format("{} {} {}\n", r, z, M_PI * r * r * fit->bekker_pressure(z, r));
      }
      plate_fit += "\n\n";
    }
    if (!c.shear.empty())
      for (double n : loads) {
        for (int i = 1; i <= 100; ++i) {
          const double a = a_max * i / 100;
          shear_fit += fmt::format("{} {} {}\n", n, a,
                                   bayes::annulus_torque(c.shear[0].inner_radius, c.shear[0].outer_radius, n, a,
                                                         fit->cohesion, fit->friction_deg, fit->janosi_k));
        }
        shear_fit += "\n\n";
      }
  }
  write_text_atomically(work + "/plate.dat", plate);
  write_text_atomically(work + "/shear.dat", shear);
  write_text_atomically(work + "/plate_fit.dat", plate_fit);
  write_text_atomically(work + "/shear_fit.dat", shear_fit);
  const int panels = (c.plate.empty() ? 0 : 1) + (c.shear.empty() ? 0 : 1);
  if (panels == 0) return;
  std::string s = fmt::format(
      "set terminal pngcairo noenhanced size {},520 font 'Sans,11'\nset output 'bevameter.png'\nset multiplot layout "
      "1,{}\nset grid\nset key top left\n",
      600 * panels, panels);
  if (!c.plate.empty()) {
    s += "set title 'Plate sinkage: points = rig, lines = SCM set'\nset xlabel 'sinkage [m]'\nset ylabel 'force "
         "[N]'\nplot ";
    int k = 0;
    for (double r : radii) {
      s += fmt::format(
          "'plate.dat' using ($1=={0} ? $2 : 1/0):3 with points pt 7 ps 0.4 lc rgb '{1}' title 'r = {0} m', ", r,
          kColours[k % 9]);
      if (fit)
        s += fmt::format("'plate_fit.dat' using ($1=={} ? $2 : 1/0):3 with lines lw 2 lc rgb '{}' notitle, ", r,
                         kColours[k % 9]);
      ++k;
    }
    s.resize(s.size() - 2);
    s += "\n";
  }
  if (!c.shear.empty()) {
    s += "set title 'Annulus shear: points = rig, lines = SCM set'\nset xlabel 'angle [rad]'\nset ylabel 'torque [N "
         "m]'\nplot ";
    int k = 0;
    for (double n : loads) {
      s += fmt::format(
          "'shear.dat' using ($1=={0} ? $2 : 1/0):3 with points pt 7 ps 0.4 lc rgb '{1}' title '{0:.4g} N', ", n,
          kColours[k % 9]);
      if (fit)
        s += fmt::format("'shear_fit.dat' using ($1=={} ? $2 : 1/0):3 with lines lw 2 lc rgb '{}' notitle, ", n,
                         kColours[k % 9]);
      ++k;
    }
    s.resize(s.size() - 2);
    s += "\n";
  }
  s += "unset multiplot\n";
  render(work, s, "bevameter.png");
  publish(work, "bevameter.png", dir);
}

void plot_wheel_models(const std::string& dir,
                       const std::vector<std::pair<std::string, std::vector<rigs::WheelResult>>>& models,
                       const WheelBand* band) {
  const std::string work = dir + "/.plot_wheel";
  std::filesystem::create_directories(work);
  std::string s =
      "set terminal pngcairo noenhanced size 1500,480 font 'Sans,11'\nset output 'wheel.png'\nset multiplot layout "
      "1,3\nset grid\nset key top left\nset xlabel 'slip'\n";
  const char* columns[3][2] = {{"2", "drawbar pull [N]"}, {"3", "torque [N m]"}, {"4", "sinkage [m]"}};
  for (std::size_t m = 0; m < models.size(); ++m) {
    std::string d;
    for (const auto& r : models[m].second) d += fmt::format("{} {} {} {}\n", r.slip, r.dbp, r.torque, r.sinkage);
    write_text_atomically(fmt::format("{}/m{}.dat", work, m), d);
  }
  const bool banded = band && !band->q05[0].empty();
  if (banded) {
    std::string d;
    for (std::size_t i = 0; i < band->q05[0].size(); ++i)
      d += fmt::format("{} {} {} {} {} {} {}\n", band->slips[i], band->q05[0][i], band->q95[0][i], band->q05[1][i],
                       band->q95[1][i], band->q05[2][i], band->q95[2][i]);
    write_text_atomically(work + "/band.dat", d);
  }
  for (std::size_t k = 0; k < 3; ++k) {
    const auto& col = columns[k];
    s += fmt::format("set ylabel '{}'\nset title '{}'\nplot ", col[1], col[1]);
    if (banded)
      s += fmt::format("'band.dat' using 1:{}:{} with filledcurves fc rgb '#c8d8f0' title 'SCM 90 % posterior band', ",
                       2 + 2 * k, 3 + 2 * k);
    for (std::size_t m = 0; m < models.size(); ++m)
      s += fmt::format("'m{}.dat' using 1:{} with linespoints lw 2 pt 7 lc rgb '{}' title '{}', ", m, col[0],
                       kColours[m % 9], models[m].first);
    s.resize(s.size() - 2);
    s += "\n";
  }
  s += "unset multiplot\n";
  render(work, s, "wheel.png");
  publish(work, "wheel.png", dir);
}

}  // namespace terracal::app

namespace terracal::app {

void plot_trajectory(const std::string& dir, const std::string& title) {
  const std::string work = dir + "/.plot_trajectory";
  std::filesystem::create_directories(work);
  std::filesystem::copy_file(dir + "/trajectory.csv", work + "/trajectory.csv");
  const std::string s = fmt::format(
      "set terminal pngcairo noenhanced size 1500,900 font 'Sans,11'\nset output 'trajectory.png'\n"
      "set datafile separator ','\nset key autotitle columnhead\nset grid\n"
      "set multiplot layout 2,3 title '{}'\n"
      "set xlabel 'x [m]'\nset ylabel 'y [m]'\nset title 'path (axes not to scale)'\nplot 'trajectory.csv' using 2:3 "
      "with lines lw 2 notitle\n"
      "set xlabel 'time [s]'\nset ylabel '[m/s]'\nset title 'speed'\nplot 'trajectory.csv' using 1:8 with lines lw 2, "
      "'' using 1:9 with lines lw 2\n"
      "set ylabel '[rad/s], [rad]'\nset title 'yaw rate and roll'\nplot 'trajectory.csv' using 1:10 with lines lw 2, "
      "'' "
      "using 1:6 with lines lw 2\n"
      "set ylabel '[m/s^2]'\nset title 'accelerations'\nplot 'trajectory.csv' using 1:12 with lines lw 2, '' using "
      "1:13 with lines lw 2\n"
      "set ylabel '[rpm]'\nset title 'engine'\nplot 'trajectory.csv' using 1:14 with lines lw 2\n"
      "set ylabel 'gear'\nset title 'gear'\nplot 'trajectory.csv' using 1:15 with steps lw 2\n"
      "unset multiplot\n",
      title);
  render(work, s, "trajectory.png");
  publish(work, "trajectory.png", dir);
}

// One panel per channel: columns 1 (time) and, per channel k, 3k-1..3k+1 (reference, preset,
// calibrated) of `csv`.
void plot_rom_fit(const std::string& dir, const std::string& csv, const std::string& png, const std::string& title,
                  const std::vector<std::pair<std::string, std::string>>& channels) {
  const std::string work = dir + "/.plot_" + png;
  std::filesystem::create_directories(work);
  std::filesystem::copy_file(dir + "/" + csv, work + "/fit.csv", std::filesystem::copy_options::overwrite_existing);
  std::string s = fmt::format(
      "set terminal pngcairo noenhanced size 1400,{} font 'Sans,11'\nset output '{}'\n"
      "set datafile separator ','\nset grid\nset key box opaque\nset xlabel 'time [s]'\n"
      "set multiplot layout {},2 title '{}'\n",
      450 * ((channels.size() + 1) / 2), png, (channels.size() + 1) / 2, title);
  for (std::size_t k = 0; k < channels.size(); ++k) {
    const std::size_t c = 2 + 3 * k;
    s += fmt::format(
        "set title '{0}'\nset ylabel '[{1}]'\nplot 'fit.csv' using 1:{2} with lines lw 3 lc rgb 'black' title "
        "'reference', '' using 1:{3} with lines lw 2 dt 2 lc rgb 'gray50' title 'preset ROM', '' using 1:{4} with "
        "lines lw 2 lc rgb 'red' title 'calibrated ROM (MAP)'\n",
        channels[k].first, channels[k].second, c, c + 1, c + 2);
  }
  s += "unset multiplot\n";
  render(work, s, png);
  publish(work, png, dir);
}

}  // namespace terracal::app
