#include "apps/pipeline_checks.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "virtual_bevameter/curve_change.hpp"

namespace terracal::app {

namespace {
// Each check reruns one rig: in a bin 1.5x larger (and deeper), and for a 1.5x longer run; each
// Check is the largest relative change of the measured curve. The rerun curves go to OUT/checks/.
std::string checks_dir(const PipelinePlan& plan) {
  const std::string dir = plan.out + "/checks";
  std::filesystem::create_directories(dir);
  return dir;
}

TerrainOptions larger_bin(const TerrainOptions& o) {
  TerrainOptions big = o;
  big.bin_scale = 1.5 * o.bin_scale;
  if (big.bin_depth_scale > 0) big.bin_depth_scale *= 1.5;
  return big;
}

// Realisation k of a CRM terrain for the bin checks (PipelinePlan::check_realisations): k = 0 is the
// terrain as given (the run the pipeline calibrates on; by default settled from the exact lattice);
// k >= 1 settles from a start jittered by 0.1 spacings (or the terrain's own jitter), drawn with seed
// settle_seed + k. The lattice and the jittered starts are all ways the same bed can be prepared, so
// the scatter between realisations includes the difference between them. The same k in both bins:
// the bins differ in size only.
TerrainOptions realisation(const TerrainOptions& o, int k) {
  TerrainOptions r = o;
  if (k == 0) return r;
  if (r.settle_jitter == 0) r.settle_jitter = 0.1;
  r.settle_seed = o.settle_seed + k;
  return r;
}
// The wheel check's slip (the sweep's middle one) and its longer run.
double check_slip(const PipelinePlan& plan) { return plan.slips[plan.slips.size() / 2]; }
rigs::WheelRun longer_run(const rigs::WheelRun& run) {
  rigs::WheelRun r = run;
  r.duration *= 1.5;
  return r;
}

std::string realisation_suffix(int k) { return k == 0 ? "" : fmt::format("_realisation{}", k); }
std::string realisations_note(int n) { return n > 1 ? fmt::format(" (means of {} realisations per bin)", n) : ""; }

// Plate: the largest plate in a 1.5x bin, 1.5x deeper, and pushed at 2/3 the speed (its stroke is
// set by the sinkage, so a longer run is a slower one); its loading leg (Bekker's law), force
// against sinkage. A rate-independent soil should not see the speed; the CRM bed does, because it
// softens with time (results/plate_bin_check, sixth study).
void check_plate(const PipelinePlan& plan, const SoilChoice& crm, const BevameterCurves& base,
                 std::vector<PipelineCheck>& out) {
  BevameterPlan p = plan.bevameter;
  p.plates = {*std::max_element(p.plates.begin(), p.plates.end())};
  auto loading_leg = [&](const std::vector<rigs::PlateRow>& rows) {
    rigs::Curve c;
    for (const auto& r : rows)
      if (r.radius == p.plates[0] && r.phase == "load") c.x.push_back(r.sinkage), c.y.push_back(r.force);
    return c;
  };
  const auto big = run_bevameter(crm, larger_bin(plan.terrain), p, true, false);
  rigs::write_plate_csv(checks_dir(plan) + "/plate_bin_1.5x.csv", big.plate);
  out.push_back({"plate", fmt::format("r = {} m, loading leg: bin 1.5x larger and deeper", p.plates[0]),
                 rigs::curve_change(loading_leg(base.plate), loading_leg(big.plate))});
  BevameterPlan slower = p;
  slower.plate_speed /= 1.5;
  slower.plate_unload_speed /= 1.5;
  const auto longer = run_bevameter(crm, plan.terrain, slower, true, false);
  rigs::write_plate_csv(checks_dir(plan) + "/plate_slower.csv", longer.plate);
  out.push_back(
      {"plate",
       fmt::format("r = {} m, loading leg: run 1.5x longer (plate at {:.3g} m/s)", p.plates[0], slower.plate_speed),
       rigs::curve_change(loading_leg(base.plate), loading_leg(longer.plate))});
}

// Annulus: the heaviest load, in a 1.5x bin, then turned at 2/3 the rate over the same angle (a
// longer run, as for the plate: the torque-angle curve of a rate-independent soil should not see
// it). Turning further instead would only extend the curve: up to the base's angle the two runs are
// the same simulation. Whether the torque has stopped rising by the end of the turn is reported
// beside the checks: under the heavier loads the ring keeps sinking as it turns (slip sinkage), so
// its torque keeps rising too (results/plate_bin_check, eleventh study).
void check_annulus(const PipelinePlan& plan, const SoilChoice& crm, const BevameterCurves& base,
                   std::vector<PipelineCheck>& out) {
  BevameterPlan s = plan.bevameter;
  s.shear_loads = {*std::max_element(s.shear_loads.begin(), s.shear_loads.end())};
  auto curve = [&](const BevameterCurves& c, double rigs::ShearRow::*f) {  // torque or sinkage against angle
    rigs::Curve t;
    for (const auto& r : c.shear)
      if (r.normal_load == s.shear_loads[0]) t.x.push_back(r.angle), t.y.push_back(r.*f);
    return t;
  };
  const int n = plan.check_realisations;
  std::vector<rigs::Curve> rigs_bin{curve(base, &rigs::ShearRow::torque)}, big_bin;
  for (int k = 0; k < n; ++k) {
    if (k > 0) {
      const auto again = run_bevameter(crm, realisation(plan.terrain, k), s, false, true);
      rigs::write_shear_csv(checks_dir(plan) + "/shear" + realisation_suffix(k) + ".csv", again.shear);
      rigs_bin.push_back(curve(again, &rigs::ShearRow::torque));
    }
    const auto big = run_bevameter(crm, realisation(larger_bin(plan.terrain), k), s, false, true);
    rigs::write_shear_csv(checks_dir(plan) + "/shear_bin_1.5x" + realisation_suffix(k) + ".csv", big.shear);
    big_bin.push_back(curve(big, &rigs::ShearRow::torque));
  }
  out.push_back({"annulus",
                 fmt::format("{:.4g} N: bin 1.5x larger and deeper{}", s.shear_loads[0], realisations_note(n)),
                 rigs::curve_change(rigs::mean_curve(rigs_bin), rigs::mean_curve(big_bin))});
  if (n > 1)
    out.push_back({"annulus",
                   fmt::format("{:.4g} N: single realisations against each other (largest pair within either bin)",
                               s.shear_loads[0]),
                   std::max(rigs::realisation_scatter(rigs_bin), rigs::realisation_scatter(big_bin)), false});
  BevameterPlan slower = s;
  slower.shear_rate /= 1.5;
  const auto longer = run_bevameter(crm, plan.terrain, slower, false, true);
  rigs::write_shear_csv(checks_dir(plan) + "/shear_slower.csv", longer.shear);
  out.push_back({"annulus",
                 fmt::format("{:.4g} N: run 1.5x longer (turned at {:.3g} rad/s over the same angle)", s.shear_loads[0],
                             slower.shear_rate),
                 rigs::curve_change(curve(base, &rigs::ShearRow::torque), curve(longer, &rigs::ShearRow::torque))});
  // The torque's rise over the turn's second half: the mean of its last fifth against its middle fifth.
  const rigs::Curve torque = curve(base, &rigs::ShearRow::torque), sinkage = curve(base, &rigs::ShearRow::sinkage);
  auto fifth_mean = [](const std::vector<double>& v, std::size_t part) {
    const std::size_t lo = part * v.size() / 5, hi = (part + 1) * v.size() / 5;
    double sum = 0;
    for (std::size_t i = lo; i < hi; ++i) sum += v[i];
    return hi > lo ? sum / double(hi - lo) : 0.0;
  };
  if (torque.y.size() >= 5) {
    const double mid = fifth_mean(torque.y, 2), last = fifth_mean(torque.y, 4);
    out.push_back({"annulus",
                   fmt::format("{:.4g} N: torque still rising at the end of the turn (last fifth against the middle "
                               "one; the ring sinks {:.3g} -> {:.3g} m)",
                               s.shear_loads[0], sinkage.y.front(), sinkage.y.back()),
                   (last - mid) / std::max(std::abs(last), 1e-12), false});
  }
}

// Wheel: the middle slip of the sweep in a 1.5x bin, and run 1.5x longer.
void check_wheel(const PipelinePlan& plan, const SoilChoice& crm, const std::vector<rigs::WheelResult>& base_sweep,
                 std::vector<PipelineCheck>& out) {
  const double slip = check_slip(plan);
  const rigs::WheelResult* base = nullptr;
  for (const auto& r : base_sweep)
    if (r.slip == slip) base = &r;
  if (!base) return;
  const int n = plan.check_realisations;
  std::vector<rigs::WheelResult> rigs_bin{*base}, big_bin;
  for (int k = 0; k < n; ++k) {
    if (k > 0) {
      const auto again =
          run_wheel_sweep(SoilModel::kCrm, crm, realisation(plan.terrain, k), plan.wheel, {slip}, plan.crm_wheel_run);
      rigs::write_wheel_series_csv(checks_dir(plan) + "/wheel" + realisation_suffix(k) + "_series.csv", again);
      rigs_bin.push_back(again[0]);
    }
    const auto big = run_wheel_sweep(SoilModel::kCrm, crm, realisation(larger_bin(plan.terrain), k), plan.wheel, {slip},
                                     plan.crm_wheel_run);
    rigs::write_wheel_series_csv(checks_dir(plan) + "/wheel_bin_1.5x" + realisation_suffix(k) + "_series.csv", big);
    big_bin.push_back(big[0]);
  }
  const rigs::WheelRun long_run = longer_run(plan.crm_wheel_run);
  const auto longer = run_wheel_sweep(SoilModel::kCrm, crm, plan.terrain, plan.wheel, {slip}, long_run);
  rigs::write_wheel_series_csv(checks_dir(plan) + "/wheel_longer_series.csv", longer);
  // The largest of the changes of DBP (relative to the thrust torque / r), torque and sinkage.
  auto change = [&](const rigs::WheelResult& from, const rigs::WheelResult& r) {
    return std::max({std::abs(r.dbp - from.dbp) / std::max(std::abs(from.torque / plan.wheel.radius), 1e-12),
                     std::abs(r.torque - from.torque) / std::max(std::abs(from.torque), 1e-12),
                     std::abs(r.sinkage - from.sinkage) / std::max(std::abs(from.sinkage), 1e-12)});
  };
  auto mean = [](const std::vector<rigs::WheelResult>& runs) {
    rigs::WheelResult m;
    for (const auto& r : runs) {
      m.dbp += r.dbp / double(runs.size());
      m.torque += r.torque / double(runs.size());
      m.sinkage += r.sinkage / double(runs.size());
    }
    return m;
  };
  auto scatter = [&](const std::vector<rigs::WheelResult>& runs) {
    double largest = 0;
    for (std::size_t a = 0; a < runs.size(); ++a)
      for (std::size_t b = a + 1; b < runs.size(); ++b)
        largest = std::max({largest, change(runs[a], runs[b]), change(runs[b], runs[a])});
    return largest;
  };
  out.push_back(
      {"wheel",
       fmt::format("slip {}: bin 1.5x larger (largest of DBP/thrust, torque, sinkage){}", slip, realisations_note(n)),
       change(mean(rigs_bin), mean(big_bin))});
  if (n > 1)
    out.push_back(
        {"wheel", fmt::format("slip {}: single realisations against each other (largest pair within either bin)", slip),
         std::max(scatter(rigs_bin), scatter(big_bin)), false});
  out.push_back({"wheel", fmt::format("slip {}: run 1.5x longer (largest of DBP/thrust, torque, sinkage)", slip),
                 change(*base, longer[0])});
}

}  // namespace

void check_pipeline_checks(const PipelinePlan& plan, const SoilChoice& crm) {
  const TerrainOptions big = larger_bin(plan.terrain);
  for (const std::string& rig : plan.checks) {
    if (rig == "plate") check_bevameter(crm, big, plan.bevameter, true, false);
    if (rig == "annulus") check_bevameter(crm, big, plan.bevameter, false, true);
    if (rig != "wheel" || plan.slips.empty()) continue;
    const std::vector<double> slip{check_slip(plan)};
    check_wheel_sweep(SoilModel::kCrm, crm, big, plan.wheel, slip, plan.crm_wheel_run);
    check_wheel_sweep(SoilModel::kCrm, crm, plan.terrain, plan.wheel, slip, longer_run(plan.crm_wheel_run));
  }
}

std::vector<PipelineCheck> run_checks(const PipelinePlan& plan, const SoilChoice& crm, const BevameterCurves& base_bev,
                                      const std::vector<rigs::WheelResult>& base_wheel) {
  std::vector<PipelineCheck> out;
  for (const std::string& rig : plan.checks) {
    if (rig == "plate") check_plate(plan, crm, base_bev, out);
    if (rig == "annulus") check_annulus(plan, crm, base_bev, out);
    if (rig == "wheel") check_wheel(plan, crm, base_wheel, out);
  }
  return out;
}

}  // namespace terracal::app
