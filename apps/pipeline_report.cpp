#include "apps/pipeline_report.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"

namespace terracal::app {

namespace {
using Field = double rigs::WheelResult::*;

// RMSE over the rows `rows` (empty: all rows).
double rmse(const std::vector<rigs::WheelResult>& a, const std::vector<rigs::WheelResult>& ref, Field f,
            const std::vector<std::size_t>& rows = {}) {
  double s = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < ref.size(); ++i) {
    if (!rows.empty() && std::find(rows.begin(), rows.end(), i) == rows.end()) continue;
    s += (a[i].*f - ref[i].*f) * (a[i].*f - ref[i].*f);
    ++n;
  }
  return std::sqrt(s / double(n));
}

bool calibrated_on(const PipelinePlan& plan, double slip) {
  if (!plan.calibrate_on_wheel) return false;
  return plan.calibration_slips.empty() ||
         std::find(plan.calibration_slips.begin(), plan.calibration_slips.end(), slip) != plan.calibration_slips.end();
}

// The sweep's rows the calibration did not see (empty when it saw every one, or none).
std::vector<std::size_t> held_out_rows(const PipelinePlan& plan) {
  std::vector<std::size_t> rows;
  if (!plan.calibrate_on_wheel) return rows;
  for (std::size_t i = 0; i < plan.slips.size(); ++i)
    if (!calibrated_on(plan, plan.slips[i])) rows.push_back(i);
  return rows;
}

double spread(const std::vector<rigs::WheelResult>& ref, Field f) {
  double lo = 1e300, hi = -1e300;
  for (const auto& r : ref) lo = std::min(lo, r.*f), hi = std::max(hi, r.*f);
  return hi - lo;
}

std::string soil_section(const PipelinePlan& plan, const PipelineResults& r) {
  const CrmSoil& s = plan.soil;
  std::string md = fmt::format("# terracal pipeline: {}\n\n", plan.soil_name);
  md += fmt::format(
      "CRM soil: density {} kg/m^3, E {} Pa, nu {}, mu_s {}, mu_2 {}, I0 {}, cohesion {} Pa, gravity {} m/s^2.\n\n",
      s.density, s.young_modulus, s.poisson_ratio, s.mu_s, s.mu_2, s.I0, s.cohesion, norm(s.gravity));
  md += fmt::format("- CRM bevameter: {}\n- CRM wheel: {}\n- SCM wheel: {}\n\n", r.bevameter.site, r.crm_wheel_site,
                    r.scm_wheel_site);
  return md;
}

std::string calibration_section(const PipelineResults& r) {
  const nlohmann::ordered_json& params = r.calibration.params;
  std::string md = "## Bevameter (CRM) and the calibrated SCM set\n\n![bevameter](bevameter.png)\n\n";
  md += "| parameter | MAP | posterior sd | 5 % | 95 % |\n|---|---|---|---|---|\n";
  for (const auto& [key, value] : params["Soil parameters"].items()) {
    const auto& post = params.contains("Posterior") && params["Posterior"].contains(key) ? params["Posterior"][key]
                                                                                         : nlohmann::ordered_json();
    auto num = [&](const char* k) {
      return post.is_object() && post.contains(k) && post[k].is_number() ? fmt::format("{:.4g}", post[k].get<double>())
                                                                         : std::string("-");
    };
    md += fmt::format("| {} | {:.4g} | {} | {} | {} |\n", key, value.get<double>(), num("sd"), num("q05"), num("q95"));
  }
  if (params.contains("Slip sinkage")) {
    const auto& post = params["Posterior"]["Slip sinkage S"];
    md += fmt::format("| Slip sinkage S (Lyasko) | {:.4g} | {:.4g} | {:.4g} | {:.4g} |\n",
                      params["Slip sinkage"]["S"].get<double>(), post["sd"].get<double>(), post["q05"].get<double>(),
                      post["q95"].get<double>());
  }
  if (params.contains("Fit") && params["Fit"].contains("annulus_law")) {
    const auto& a = params["Fit"]["annulus_law"];
    md += fmt::format(
        "\nThe annulus's law was scaled: its torque is the set's Mohr-Coulomb strength over R = {:.3g}, developed "
        "over its own Janosi k = {:.3g} m (`--annulus-law`). The annulus gave how the strength grows with the load, "
        "the wheel its level and k.\n",
        a["strength_ratio_R"].get<double>(), a["annulus_janosi_k_m"].get<double>());
  }
  if (params.contains("Fit") && params["Fit"].contains("elastic_stiffness") &&
      params["Fit"]["elastic_stiffness"].contains("given_Pa_m")) {
    const auto& e = params["Fit"]["elastic_stiffness"];
    md += fmt::format(
        "\nThe set's elastic stiffness was given: {:.3g} Pa/m (`--elastic-stiffness`); the plates' unload rows give "
        "{:.3g} Pa/m.\n",
        e["given_Pa_m"].get<double>(), e["plates_fit_Pa_m"].get<double>());
  }
  md += fmt::format("\nCalibrated on {}. Calibration: {} (calibration/summary.txt).\n\n",
                    params.contains("Slip sinkage") ? "the bevameter curves and the CRM wheel (the steady SCM wheel, "
                                                      "with slip sinkage)"
                                                    : "the bevameter curves",
                    r.calibration.converged ? "converged" : "NOT converged");
  if (!r.scm_note.empty()) md += "**Note.** " + r.scm_note + "\n\n";
  return md;
}

// What the CRM set-up leaves out that the checked one has (docs/decisions.md): a smaller plate bin,
// the hourglass effects off.
std::string crm_setup_notes(const PipelinePlan& plan) {
  std::string md;
  const BevameterPlan checked;
  const double walls = plan.bevameter.plate_wall_radii * plan.bevameter.bin_scale * plan.terrain.bin_scale;
  const double depth = plan.bevameter.plate_depth_scale * plan.bevameter.bin_scale * plan.terrain.depth_scale();
  if (walls < checked.plate_wall_radii - 1e-9 || depth < checked.plate_depth_scale - 1e-9)
    md += fmt::format(
        "**Note.** The CRM plate bin (walls {:.3g} plate radii away, soil {:.3g} x (max sinkage + 2.5 radii)) is "
        "smaller than "
        "the checked bin ({:.3g} radii, {:.3g}x): the plate curves read high (4-8 % at 9 radii and 2x, 20-40 % at 3 "
        "radii and "
        "1x; results/plate_bin_check).\n\n",
        walls, depth, checked.plate_wall_radii, checked.plate_depth_scale);
  if (plan.terrain.hourglass_damping <= 0)
    md +=
        "**Note.** The CRM effect hourglass_damping is off: the lattice's checkerboard mode softens the bed, so the "
        "CRM curves read "
        "lower at finer spacing and in larger bins (results/plate_bin_check).\n\n";
  if (plan.terrain.hourglass_stiffness <= 0)
    md +=
        "**Note.** The CRM effect hourglass_stiffness is off: soil escapes from under the plates through the "
        "checkerboard mode, so "
        "the plate curves read low and fall with a slower or longer test (results/plate_bin_check).\n\n";
  return md;
}

// The SCM wheel's posterior band and its check against the time-stepping wheel.
std::string band_section(const WheelBand& b) {
  if (b.sets == 0) return "";
  std::string md = fmt::format(
      "\nThe plot's shaded band is SCM's 90 % posterior band: {} posterior sets through the steady SCM wheel{}. "
      "Checked against the time-stepping SCM wheel at slip {}:\n\n",
      b.sets, b.failed > 0 ? fmt::format(" ({} more had no steady state)", b.failed) : std::string(), b.check_slip);
  md += "| set | DBP steady / time-stepping [N] | torque [N m] | sinkage [m] |\n|---|---|---|---|\n";
  for (std::size_t k = 0; k < b.check_steady.size(); ++k) {
    const auto &a = b.check_steady[k], &t = b.check_stepped[k];
    md += fmt::format("| {} | {:.4g} / {:.4g} | {:.4g} / {:.4g} | {:.4g} / {:.4g} |\n", k + 1, a[0], t[0], a[1], t[1],
                      a[2], t[2]);
  }
  return md;
}

std::string wheel_section(const PipelinePlan& plan, const PipelineResults& r) {
  const auto &crm = r.wheel_crm, &scm = r.wheel_scm, &wr = r.wheel_wong_reece;
  std::string md =
      fmt::format("## Single wheel (radius {} m, width {} m, mass {} kg, omega {} rad/s)\n\n![wheel](wheel.png)\n\n",
                  plan.wheel.radius, plan.wheel.width, plan.wheel.mass, plan.wheel.angular_velocity);
  md +=
      "| slip | DBP CRM [N] | DBP SCM | DBP W-R | torque CRM [N m] | torque SCM | torque W-R | sinkage CRM [m] | "
      "sinkage SCM | sinkage W-R |\n";
  md += "|---|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < plan.slips.size(); ++i)
    md += fmt::format("| {}{} | {:.4g} | {:.4g} | {:.4g} | {:.4g} | {:.4g} | {:.4g} | {:.4g} | {:.4g} | {:.4g} |\n",
                      plan.slips[i], calibrated_on(plan, plan.slips[i]) ? " (c)" : "", crm[i].dbp, scm[i].dbp, wr[i].dbp, crm[i].torque, scm[i].torque, wr[i].torque,
                      crm[i].sinkage, scm[i].sinkage, wr[i].sinkage);
  md += "\n" + rigs::steadiness_summary("CRM", crm) + " " + rigs::steadiness_summary("SCM", scm) + "\n";
  if (plan.calibrate_on_wheel) md += "\n(c): a slip the calibration saw.\n";
  md += band_section(r.scm_band);
  md += "\n## Error against CRM (RMSE over the slips; in brackets, relative to CRM's range over all the slips)\n\n";
  md += "| model | slips | DBP [N] | torque [N m] | sinkage [m] |\n|---|---|---|---|---|\n";
  const std::vector<std::size_t> held_out = held_out_rows(plan);
  for (const auto& [name, res] : {std::pair{"SCM (calibrated)", &scm}, std::pair{"Wong-Reece (calibrated)", &wr}}) {
    for (const bool only_held_out : {false, true}) {
      if (only_held_out && held_out.empty()) continue;
      const std::vector<std::size_t> rows = only_held_out ? held_out : std::vector<std::size_t>{};
      auto cell = [&](Field f) {
        const double e = rmse(*res, crm, f, rows), range = spread(crm, f);
        return range > 0 ? fmt::format("{:.4g} ({:.0f} %)", e, 100 * e / range) : fmt::format("{:.4g}", e);
      };
      md += fmt::format("| {} | {} | {} | {} | {} |\n", name, only_held_out ? "held out" : "all",
                        cell(&rigs::WheelResult::dbp), cell(&rigs::WheelResult::torque),
                        cell(&rigs::WheelResult::sinkage));
    }
  }
  return md;
}

std::string checks_and_cost_section(const PipelineResults& r) {
  std::string md;
  if (!r.checks.empty()) {
    md += "\n## Bin size and run length\n\n| rig | check | largest change of the curve |\n|---|---|---|\n";
    for (const auto& c : r.checks)
      md += fmt::format("| {} | {} | {:.2f} % {} |\n", c.rig, c.what, 100 * c.change,
                        !c.bounded        ? "(a measurement, no bound)"
                        : c.change < 0.05 ? ""
                                          : "(above 5 %)");
  }
  const StageTimes& w = r.wall;
  md += fmt::format(
      "\n## Cost\n\n| stage | wall time [s] |\n|---|---|\n| CRM bevameter | {:.1f} |\n| calibration | {:.1f} |\n"
      "| CRM wheel sweep | {:.1f} |\n| SCM wheel sweep | {:.2f} |\n| total | {:.1f} |\n{}",
      w.bevameter, w.calibration, w.crm_wheel, w.scm_wheel, w.total,
      w.crm_at_once
          ? "\nThe CRM runs went at once (`--concurrent-runs`): the CRM bevameter and wheel sweep overlap in time.\n"
          : "");
  return md;
}

nlohmann::json errors_json(const std::vector<rigs::WheelResult>& model, const std::vector<rigs::WheelResult>& crm,
                           const std::vector<std::size_t>& rows = {}) {
  return {{"dbp_N", rmse(model, crm, &rigs::WheelResult::dbp, rows)},
          {"torque_Nm", rmse(model, crm, &rigs::WheelResult::torque, rows)},
          {"sinkage_m", rmse(model, crm, &rigs::WheelResult::sinkage, rows)}};
}

nlohmann::json summary_json(const PipelinePlan& plan, const PipelineResults& r) {
  const StageTimes& w = r.wall;
  nlohmann::json summary = {{"soil", plan.soil_name},
                            {"calibration_converged", r.calibration.converged},
                            {"note", r.scm_note},
                            {"wall_seconds",
                             {{"bevameter", w.bevameter},
                              {"calibration", w.calibration},
                              {"crm_wheel", w.crm_wheel},
                              {"scm_wheel", w.scm_wheel},
                              {"total", w.total}}},
                            {"rmse_scm_vs_crm", errors_json(r.wheel_scm, r.wheel_crm)},
                            {"rmse_wong_reece_vs_crm", errors_json(r.wheel_wong_reece, r.wheel_crm)}};
  nlohmann::json checks = nlohmann::json::array();
  for (const auto& c : r.checks)
    checks.push_back({{"rig", c.rig}, {"check", c.what}, {"relative_change", c.change}, {"bounded", c.bounded}});
  summary["checks"] = checks;
  summary["calibrated_on"] = plan.calibrate_on_wheel ? "bevameter+wheel" : "bevameter";
  if (r.scm_band.sets > 0) {
    double worst = 0;  // the largest steady-vs-time-stepping difference, in % of the time-stepped value
    for (std::size_t k = 0; k < r.scm_band.check_steady.size(); ++k)
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, 100 * std::abs(r.scm_band.check_steady[k][c] - r.scm_band.check_stepped[k][c]) /
                                    std::max(std::abs(r.scm_band.check_stepped[k][c]), 1e-12));
    summary["scm_band"] = {{"sets", r.scm_band.sets},
                           {"failed", r.scm_band.failed},
                           {"check_slip", r.scm_band.check_slip},
                           {"checks", r.scm_band.check_steady.size()},
                           {"largest_check_difference_percent", worst}};
  }
  if (const auto held_out = held_out_rows(plan); !held_out.empty()) {
    std::vector<double> slips;
    for (std::size_t i : held_out) slips.push_back(plan.slips[i]);
    summary["held_out_slips"] = slips;
    summary["rmse_scm_vs_crm_held_out"] = errors_json(r.wheel_scm, r.wheel_crm, held_out);
  }
  return summary;
}

}  // namespace

void write_pipeline_report(const PipelinePlan& plan, const PipelineResults& r) {
  const std::string md = soil_section(plan, r) + calibration_section(r) + crm_setup_notes(plan) +
                         wheel_section(plan, r) + checks_and_cost_section(r);
  write_text_atomically(plan.out + "/report.md", md);
  write_text_atomically(plan.out + "/summary.json", summary_json(plan, r).dump(2) + "\n");
}

}  // namespace terracal::app
