// `terracal wheel`: a single-wheel slip sweep on CRM, SCM or the analytic Wong-Reece model;
// writes wheel.csv (steady means) and wheel_series.csv (time series).
#include <chrono>
#include <filesystem>
#include <memory>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "apps/cli_checks.hpp"
#include "apps/commands.hpp"
#include "apps/out_dir.hpp"
#include "apps/report_plots.hpp"
#include "apps/soil_choice.hpp"
#include "core/atomic_file.hpp"
#include "core/errors.hpp"

namespace terracal::app {

namespace {
struct WheelArgs {
  SoilModel terrain = SoilModel::kCrm;
  std::string wheel, slips = kDefaultSlips, out;
  double duration = 4.0, average_from = 0.5, drop_height = 0;
  bool plots = true, with_wong_reece = false;
  TerrainOptions options;
};
}  // namespace

Command add_wheel(CLI::App& app) {
  auto* sub = app.add_subcommand("wheel", "Single-wheel slip sweep on CRM, SCM or Wong-Reece; writes wheel.csv");
  auto a = std::make_shared<WheelArgs>();
  add_choice(sub, "--terrain", a->terrain, soil_model_names(), "soil model: crm, scm or wong-reece")
      ->required()
      ->default_str("");
  sub->add_option("--wheel", a->wheel, "wheel file (JSON, docs/formats.md 'Wheel')")->required();
  sub->add_option("--slips", a->slips, "slips, comma-separated (negative: skid)")
      ->check(list_in_range(rigs::WheelRanges::kSlip))
      ->capture_default_str();
  sub->add_option("--out", a->out, "output folder")->required();
  sub->add_option("--duration", a->duration, "simulated seconds per slip")
      ->check(in_range(rigs::WheelRanges::kDuration))
      ->capture_default_str();
  sub->add_option("--average-from", a->average_from, "steady means over t >= this fraction of the run")
      ->check(in_range(rigs::WheelRanges::kAverageFrom))
      ->capture_default_str();
  sub->add_option("--drop-height", a->drop_height,
                  "CRM, SCM: the wheel starts this far above the surface and falls onto it (a drop test)")
      ->check(in_range(rigs::WheelRanges::kDropHeight))
      ->capture_default_str();
  sub->add_flag("!--no-plots", a->plots, "skip the PNG plot");
  sub->add_flag("--with-wong-reece", a->with_wong_reece,
                "with --terrain scm: also the Wong-Reece model of the same set (wheel_wong_reece.csv, comparison.md)");
  add_terrain_options(sub, a->options, true, true);
  auto* tolerance = sub->add_option("--wong-reece-tolerance", a->options.wong_reece_tolerance,
                                    "Wong-Reece: relative tolerance of the entry-angle root and of each quadrature")
                        ->check(in_range(Range{1e-14, 1e-3}))
                        ->capture_default_str();
  sub->add_flag("--wong-reece-slip-sinkage", a->options.wong_reece_slip_sinkage,
                "with --terrain wong-reece: Lyasko's slip sinkage (S from the set's 'Slip sinkage' block, 1.5 if "
                "absent); --with-wong-reece follows --scm-effects slip_sinkage");
  return [a, tolerance] {
    const OutDir out = prepare_out_dir("--out", a->out);
    if (a->with_wong_reece && a->terrain != SoilModel::kScm)
      throw InputError("--with-wong-reece: only with --terrain scm");
    if (tolerance->count() > 0 && a->terrain != SoilModel::kWongReece && !a->with_wong_reece)
      throw InputError(fmt::format("--wong-reece-tolerance {}: only with --terrain wong-reece or --with-wong-reece",
                                   a->options.wong_reece_tolerance));
    if (a->drop_height > 0 && a->terrain == SoilModel::kWongReece)
      throw InputError(fmt::format("--drop-height {} m: Wong-Reece is a steady model (no fall, no impact); drop tests "
                                   "run on --terrain scm or crm",
                                   a->drop_height));
    if (a->options.wong_reece_slip_sinkage && a->terrain != SoilModel::kWongReece)
      throw InputError("--wong-reece-slip-sinkage: only with --terrain wong-reece (SCM: --scm-effects slip_sinkage)");
    const rigs::WheelSpec wheel = rigs::read_wheel_json(a->wheel);
    const auto slips = parse_list(a->slips, "--slips");
    rigs::WheelRun run;
    run.duration = a->duration;
    run.average_from = a->average_from;
    run.drop_height = a->drop_height;
    const SoilChoice soil = choose_soil(a->terrain, a->options);
    check_wheel_sweep(a->terrain, soil, a->options, wheel, slips, run);
    warn_about_sweep(wheel, slips);
    std::filesystem::create_directories(a->out);
    std::string site;
    const auto start = std::chrono::steady_clock::now();
    const auto results = run_wheel_sweep(a->terrain, soil, a->options, wheel, slips, run, &site);
    // The runs' own walls add up to more than the sweep took when they go at once (--concurrent-runs).
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    rigs::write_wheel_csv(a->out + "/wheel.csv", results);
    if (a->terrain != SoilModel::kWongReece) rigs::write_wheel_series_csv(a->out + "/wheel_series.csv", results);
    double wall = 0;
    for (const auto& r : results) wall += r.wall_seconds;
    nlohmann::json j = {{"terrain", soil_model_name(a->terrain)},
                        {"site", site},
                        {"wheel", rigs::wheel_json(wheel)},
                        {"wall_seconds", wall},
                        {"elapsed_seconds", elapsed},
                        {"simulated_seconds_per_slip", run.duration}};
    write_text_atomically(a->out + "/run.json", j.dump(2) + "\n");
    std::vector<std::pair<std::string, std::vector<rigs::WheelResult>>> models = {
        {soil_model_name(a->terrain), results}};
    if (a->with_wong_reece) {
      const auto wr = run_wheel_sweep(SoilModel::kWongReece, soil, a->options, wheel, slips, run);
      rigs::write_wheel_csv(a->out + "/wheel_wong_reece.csv", wr);
      std::string md =
          "| slip | DBP SCM [N] | DBP W-R [N] | torque SCM [N m] | torque W-R [N m] | sinkage SCM [m] | sinkage W-R "
          "[m] | sinkage SCM / W-R |\n";
      md += "|---|---|---|---|---|---|---|---|\n";
      for (std::size_t i = 0; i < wr.size(); ++i)
        md += fmt::format("| {} | {:.1f} | {:.1f} | {:.1f} | {:.1f} | {:.4f} | {:.4f} | {:.2f} |\n", slips[i],
                          results[i].dbp, wr[i].dbp, results[i].torque, wr[i].torque, results[i].sinkage, wr[i].sinkage,
                          results[i].sinkage / wr[i].sinkage);
      md += "\n" + rigs::steadiness_summary("SCM", results) + "\n";
      write_text_atomically(a->out + "/comparison.md", md);
      models.push_back({"Wong-Reece", wr});
    }
    if (a->plots) plot_wheel_models(a->out, models);
    fmt::print("wheel ({}): {} slips in {:.3g} s wall (the runs' own walls: {:.3g} s); written to {}/wheel.csv\n",
               soil_model_name(a->terrain), results.size(), elapsed, wall, a->out);
    return 0;
  };
}

}  // namespace terracal::app
