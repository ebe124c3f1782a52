#include "apps/rom_pipeline_report.hpp"

#include <cmath>
#include <filesystem>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "core/gnuplot.hpp"

namespace terracal::app {

namespace {

std::string number(double v, const char* fmt_spec = "{:.3g}") {
  return std::isfinite(v) ? fmt::format(fmt::runtime(fmt_spec), v) : "–";
}

std::string parameters_table(const RomCalibrationOutcome& c) {
  std::string md = "| parameter | MAP | median | 90 % interval | R-hat | bulk ESS |\n|---|---|---|---|---|---|\n";
  const auto& r = c.result;
  for (std::size_t i = 0; i < r.summary.size() && i < r.names.size(); ++i) {
    const auto& v = r.summary[i];
    const double map = Eigen::Index(i) < r.point.x.size() ? r.point.x[i] : NAN;
    md += fmt::format("| {} | {} | {} | {} – {} | {} | {} |\n", r.names[i], number(map, "{:.4g}"),
                      number(v.q50, "{:.4g}"), number(v.q05, "{:.4g}"), number(v.q95, "{:.4g}"),
                      number(v.rhat, "{:.3f}"), number(v.ess_bulk, "{:.0f}"));
  }
  return md;
}

std::string validation_table(const RomValidationOutcome& v) {
  std::string md =
      "| manoeuvre | channel | RMSE preset | RMSE MAP | RMSE median | model band coverage | predictive band coverage |\n"
      "|---|---|---|---|---|---|---|\n";
  for (const auto& ref : v.references)
    for (const auto& ch : ref.channels)
      md += fmt::format("| {} | {} [{}] | {} | {} | {} | {:.0f} % | {:.0f} % |\n", ref.name,
                        rom::kRomChannelNames[ch.channel], rom::kRomChannelUnits[ch.channel], number(ch.rmse_preset),
                        number(ch.rmse_map), number(ch.rmse_median), 100 * ch.coverage_model,
                        100 * ch.coverage_predictive);
  return md;
}

std::string accuracy_cost_table(const std::vector<AccuracyCostRow>& rows) {
  std::string md =
      "| manoeuvre | model | device | vx RMSE [m/s] | yaw-rate RMSE [rad/s] | wall per simulated second [s] |\n"
      "|---|---|---|---|---|---|\n";
  for (const auto& r : rows)
    md += fmt::format("| {} | {} | {} | {} | {} | {:.3g} |\n", r.maneuver, r.solver, r.device,
                      r.solver == "full vehicle" ? "(reference)" : number(r.vx_rmse, "{:.3f}"),
                      r.solver == "full vehicle" ? "(reference)" : number(r.yaw_rate_rmse, "{:.4f}"),
                      r.wall_per_simulated_second);
  return md;
}

// A number, or an empty cell where there is none (a batch row has no single run to score).
std::string cell(double v) { return std::isfinite(v) ? fmt::format("{:.9g}", v) : ""; }

void write_csv(const std::string& path, const std::vector<AccuracyCostRow>& rows) {
  std::string csv = "maneuver,model,device,vx_rmse_m_s,yaw_rate_rmse_rad_s,wall_per_simulated_second\n";
  for (const auto& r : rows)
    csv += fmt::format("{},{},{},{},{},{:.9g}\n", r.maneuver, r.solver, r.device, cell(r.vx_rmse),
                       cell(r.yaw_rate_rmse), r.wall_per_simulated_second);
  write_text_atomically(path, csv);
}

// Yaw-rate error against wall time per simulated second, one point per model and manoeuvre; the
// full vehicle, the reference, at zero error. Drawn in a work folder, then committed.
void plot(const std::string& dir, const std::vector<AccuracyCostRow>& rows) {
  std::string data;
  for (const auto& r : rows)
    if (r.solver != "full vehicle" && std::isfinite(r.yaw_rate_rmse))
      data += fmt::format("\"{}: {}\" {:.9g} {:.9g}\n", r.maneuver, r.solver, r.wall_per_simulated_second,
                          r.yaw_rate_rmse);
  data += "\n\n";
  for (const auto& r : rows)
    if (r.solver == "full vehicle")
      data += fmt::format("\"{}: full vehicle\" {:.9g} 0\n", r.maneuver, r.wall_per_simulated_second);
  const std::string work = dir + "/.accuracy_cost_plot";
  std::filesystem::create_directories(work);
  write_text_atomically(work + "/accuracy_cost.dat", data);
  const std::string script =
      "set terminal pngcairo noenhanced size 1100,640 font 'Sans,11'\n"
      "set output 'accuracy_cost.png'\nset logscale x\nset grid\nset key top center\n"
      "set xlabel 'wall time per simulated second [s] (one core)'\n"
      "set ylabel 'yaw-rate RMSE against the full vehicle [rad/s]'\n"
      "set title 'Each model against the full vehicle on the validation manoeuvres'\n"
      "set offsets graph 0.02, graph 0.2, graph 0.1, graph 0.02\nset format x '%g'\n"
      "plot 'accuracy_cost.dat' index 0 using 2:3 with points pt 7 ps 1.5 title 'ROMs (preset and calibrated)', "
      "'' index 0 using 2:3:1 with labels offset 1,0 left font ',8' notitle, "
      "'' index 1 using 2:3 with points pt 5 ps 2 title 'full vehicle (the reference)', "
      "'' index 1 using 2:3:1 with labels offset -1,1 right font ',8' notitle\n";
  try {
    run_gnuplot(script, work);
    commit_file(work + "/accuracy_cost.png", dir + "/accuracy_cost.png");
  } catch (...) {
    std::error_code ec;
    std::filesystem::remove_all(work, ec);
    throw;
  }
  std::error_code ec;
  std::filesystem::remove_all(work, ec);
}

}  // namespace

void write_rom_pipeline_report(const RomPipelineSettings& s, const RomPipelineOutcome& o,
                               const RomCalibrationOutcome& calibration, const RomValidationOutcome& validation) {
  write_csv(s.out + "/accuracy_cost.csv", o.accuracy_cost);
  bool plotted = false;
  if (s.plots) {
    if (!gnuplot_available()) {
      spdlog::warn("pipeline-rom: gnuplot not found: accuracy_cost.png not drawn");
    } else {
      try {
        plot(s.out, o.accuracy_cost);
        plotted = true;
      } catch (const RunError& e) {
        spdlog::warn("pipeline-rom: accuracy_cost.png: {}", e.what());
      }
    }
  }
  std::string md = fmt::format(
      "# ROM pipeline: {} ({}) calibrated on the full vehicle\n\n"
      "The full vehicle (`{}`, rigid ground) drove the training manoeuvres accel, step_left, step_right and dlc "
      "(`full/`, the manoeuvres in `maneuvers/`); the {} ROM was calibrated on them (`calibration/`, as "
      "`terracal calibrate-rom`) and validated on sine and turn, which it did not see (`validation/`, as "
      "`terracal validate-rom`, {} posterior draws on {}).\n\n",
      rom::model_name(s.model), s.rom_vehicle.empty() ? s.vehicle : s.rom_vehicle, s.vehicle,
      rom::model_name(s.model), validation.draws, validation.device);
  md += fmt::format(
      "## Calibration\n\n{}{} ({} runs, {} failed, {:.3g} s). MAP: the point estimate (least squares), which "
      "`calibration/rom_params.json` holds; the rest from the draws.\n\n{}\n",
      o.converged ? "" : "**", calibration.result.termination + (o.converged ? "" : "**"), calibration.runs,
      calibration.failed_runs, calibration.wall_seconds, parameters_table(calibration));
  md += "## Validation (manoeuvres not used for calibration)\n\n" + validation_table(validation) +
        "\nPlots: `validation/band_<manoeuvre>.png`; details: `validation/report.md`.\n\n";
  md += "## Accuracy against cost\n\nEach model's error against the full vehicle on the validation manoeuvres, "
        "driven by the full vehicle's own inputs (`full/<manoeuvre>/inputs.txt`), next to its wall time per "
        "simulated second (single runs: the fastest of three; the batch: its wall time over draws x simulated "
        "seconds).\n\n" +
        accuracy_cost_table(o.accuracy_cost) +
        (plotted ? "\n![accuracy against cost](accuracy_cost.png)\n\n" : "\n") +
        "Data: `accuracy_cost.csv`.\n\n";
  md += fmt::format(
      "## Wall time\n\n| stage | wall [s] |\n|---|---|\n| full-vehicle runs | {:.3g} |\n| calibration | {:.3g} |\n"
      "| validation | {:.3g} |\n| comparison | {:.3g} |\n| total | {:.3g} |\n",
      o.full_seconds, o.calibration_seconds, o.validation_seconds, o.comparison_seconds, o.total_seconds);
  write_text_atomically(s.out + "/report.md", md);
  nlohmann::json j = {{"vehicle", s.vehicle},
                      {"model", rom::model_name(s.model)},
                      {"converged", o.converged},
                      {"termination", calibration.result.termination},
                      {"wall_seconds",
                       {{"full_vehicle", o.full_seconds},
                        {"calibration", o.calibration_seconds},
                        {"validation", o.validation_seconds},
                        {"comparison", o.comparison_seconds},
                        {"total", o.total_seconds}}}};
  for (const auto& r : o.accuracy_cost)
    j["accuracy_cost"].push_back({{"maneuver", r.maneuver},
                                  {"model", r.solver},
                                  {"device", r.device},
                                  {"vx_rmse", std::isfinite(r.vx_rmse) ? nlohmann::json(r.vx_rmse) : nlohmann::json()},
                                  {"yaw_rate_rmse", std::isfinite(r.yaw_rate_rmse) ? nlohmann::json(r.yaw_rate_rmse)
                                                                                   : nlohmann::json()},
                                  {"wall_per_simulated_second", r.wall_per_simulated_second}});
  write_text_atomically(s.out + "/summary.json", j.dump(2) + "\n");
}

}  // namespace terracal::app
