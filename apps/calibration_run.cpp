#include "apps/calibration_run.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "apps/memory_check.hpp"
#include "bayes/calibration_outputs.hpp"
#include "bayes/point_estimate.hpp"
#include "bayes/posterior_h5.hpp"
#include "core/atomic_file.hpp"
#include "core/checksum.hpp"
#include "core/errors.hpp"
#include "core/gnuplot.hpp"
#include "core/json_file.hpp"
#include "lowfi/slip_sinkage.hpp"
#include "terracal_version.hpp"

namespace terracal::app {
namespace fs = std::filesystem;
using namespace terracal::bayes;

namespace {

// Every number the calibration sees, in full precision: two runs with the same text saw the same data.
std::string data_text(const CalibrationData& d) {
  std::string s;
  for (const auto& p : d.plate.points)
    s += fmt::format("{:.17g},{:.17g},{:.17g},{};", p.radius, p.sinkage, p.force, int(p.phase));
  s += "|";
  if (d.shear)
    for (const auto& p : d.shear->points)
      s += fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{};", p.inner_radius, p.outer_radius, p.normal_load,
                       p.angle, p.torque, p.developed);
  s += "|";
  if (d.wheel) {
    const auto& w = d.wheel->wheel;
    s += fmt::format("{:.17g},{:.17g},{:.17g};", w.radius, w.width, w.angular_velocity);
    for (const auto& p : d.wheel->points)
      s += fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g};", p.slip, p.load, p.dbp, p.torque, p.sinkage);
  }
  s += "|";
  for (const Prior& p : d.priors)
    s += fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g};", int(p.kind), p.lower, p.upper, p.mean, p.sd,
                     p.value);
  return s;
}

// FNV-1a: a stable 64-bit fingerprint of the data and options, so that a checkpoint is resumed only
// by the very same calibration.
std::string fingerprint(const CalibrationData& d, const CalibrationSettings& s) {
  const std::string text =
      fmt::format("{}|{}|{}|{}|{}|{}|{}|{}{}{}{}", TERRACAL_VERSION, data_text(d), s.seed, s.chains, s.min_ess,
                  s.max_draws, sampler_name(s.sampler), noise_name(s.noise), s.correlated_noise ? "|ar1" : "",
                  s.annulus_law == bayes::AnnulusLaw::kScaled ? "|annulus scaled" : "",
                  s.elastic_stiffness > 0 ? fmt::format("|Ke {:a}", s.elastic_stiffness) : "");
  return fnv1a64_hex(text);
}

void validate(const CalibrationSettings& s) {
  using R = CalibrationRanges;
  if (s.chains < R::kMinChains || s.chains > R::kMaxChains)
    throw InputError(fmt::format("--chains {}: expected {} to {} chains", s.chains, R::kMinChains, R::kMaxChains));
  if (s.max_draws < R::kMinDraws || s.max_draws > R::kMaxDraws)
    throw InputError(
        fmt::format("--max-draws {}: expected {} to {} draws per chain", s.max_draws, R::kMinDraws, R::kMaxDraws));
  check_range(R::kMinEss, s.min_ess, "--min-ess");
  if (s.elastic_stiffness != 0) check_range(R::kElasticStiffness, s.elastic_stiffness, "--elastic-stiffness");
  // A run that does not converge keeps every draw up to the cap: 6 parameters and the log density in
  // doubles, held about four times over (the chains, the result, the diagnostics' copy, the checkpoint).
  const double values = double(s.chains) * double(s.max_draws) * (kNumParams + 1);
  check_memory(fmt::format("--max-draws {} with --chains {}", s.max_draws, s.chains),
               fmt::format("keeping {:.3g} draws of {} chains until the cap", double(s.max_draws), s.chains),
               4 * sizeof(double) * values, 0, "fewer --max-draws or --chains");
  if (s.out_dir.empty()) throw InputError("--out: an output folder is required");
  if (fs::exists(s.out_dir) && !fs::is_directory(s.out_dir))
    throw InputError(fmt::format("--out {}: exists and is not a folder", s.out_dir));
}

CalibrationOptions sampler_options(const CalibrationData& data, const CalibrationSettings& s) {
  CalibrationOptions opt;
  opt.seed = s.seed;
  opt.chains = s.chains;
  opt.min_ess = s.min_ess;
  opt.max_draws = s.max_draws;
  opt.sampler = s.sampler;
  opt.checkpoint_path = s.out_dir + "/.checkpoint.cbor";
  opt.fingerprint = fingerprint(data, s);
  opt.progress = [](const CalibrationProgress& p) {
    if (p.stage == "resumed")
      spdlog::info("{}", p.message);
    else if (p.stage == "restarted")
      spdlog::warn("{}", p.message);
    else if (p.stage == "warm-up")
      spdlog::info("warm-up done; sampling until R-hat and ESS targets are met");
    else
      spdlog::info("{} draws per chain: max R-hat {:.4f}, min bulk ESS {:.0f}", p.draws_per_chain, p.max_rhat,
                   p.min_ess);
  };
  return opt;
}

// Files of an earlier run in the same folder go first: the folder never mixes two runs' outputs.
void remove_earlier_outputs(const std::string& dir) {
  for (const char* old : {"scm_params.json", "posterior.h5", "summary.txt", "plate_fit.png", "shear_fit.png",
                          "shear_developed.png", "pairs.png", "wheel_dbp_fit.png", "wheel_torque_fit.png",
                          "wheel_sinkage_fit.png"})
    fs::remove(fs::path(dir) / old);
}

// --noise-correlation ar1: the residuals' correlation times at a first least-squares point (white
// noise), after which the calibration runs on the tempered likelihood.
void set_correlation_times(CalibrationProblem& problem, std::uint64_t seed) {
  PointEstimateOptions o;
  o.seed = seed;
  const PointEstimate first = estimate_point(problem, o);
  const std::vector<double> tau = problem.correlation_times(first.map);
  problem.set_correlation_times(tau);
  std::vector<std::string> text;
  for (int t = 0; t < problem.num_types(); ++t)
    text.push_back(fmt::format("{} {:.3g} ({} rows count as {:.3g})", problem.set(t).name, tau[t],
                               problem.set(t).size(), problem.effective_rows(t)));
  spdlog::info("residual correlation times: {}", fmt::join(text, ", "));
}

}  // namespace

std::string sampler_name(SamplerKind kind) { return kind == SamplerKind::kDram ? "dram" : "ensemble"; }
std::string noise_name(NoiseModel model) { return model == NoiseModel::kRelative ? "relative" : "absolute"; }

WheelGeometry wheel_geometry(const rigs::WheelSpec& wheel, const std::string& where) {
  if (wheel.grouser_count > 0)
    spdlog::warn("{}: the wheel has {} grousers; the steady SCM wheel the calibration fits is a smooth rim of the "
                 "same radius",
                 where, wheel.grouser_count);
  return WheelGeometry{wheel.radius, wheel.width, wheel.angular_velocity};
}

namespace {
// The wheel a wheel.csv was run with: the wheel file given, or `terracal wheel`'s run.json beside it.
WheelGeometry wheel_of_csv(const CalibrationFiles& files) {
  if (!files.wheel_spec.empty()) return wheel_geometry(rigs::read_wheel_json(files.wheel_spec), files.wheel_spec);
  const std::string run = (fs::path(files.wheel_csv).parent_path() / "run.json").string();
  if (!fs::exists(run))
    throw InputError(fmt::format("--wheel {}: the wheel's radius and width are needed: give --wheel-spec WHEEL.json, "
                                 "or keep the run.json that `terracal wheel` wrote beside it ({} not found)",
                                 files.wheel_csv, run));
  const nlohmann::json j = read_json_file(run, "wheel run file");
  if (!j.is_object() || !j.contains("wheel"))
    throw InputError(fmt::format("{}: key 'wheel' missing (written by `terracal wheel` since it records its wheel); "
                                 "give --wheel-spec WHEEL.json",
                                 run));
  return wheel_geometry(rigs::parse_wheel(j["wheel"], run + ": key 'wheel'"), run);
}
}  // namespace

CalibrationData read_calibration_files(const CalibrationFiles& files) {
  CalibrationData d{load_plate_csv(files.plate_csv), std::nullopt, default_priors(), std::nullopt};
  if (!files.shear_csv.empty()) d.shear = load_shear_csv(files.shear_csv);
  if (!files.wheel_csv.empty()) d.wheel = load_wheel_csv(files.wheel_csv, wheel_of_csv(files));
  if (files.wheel_csv.empty() && !files.wheel_spec.empty())
    throw InputError(fmt::format("--wheel-spec {}: only with --wheel W.csv", files.wheel_spec));
  if (!files.priors_json.empty()) d.priors = load_priors(files.priors_json);
  return d;
}

WheelData wheel_calibration_data(const std::vector<rigs::WheelResult>& runs, const rigs::WheelSpec& wheel,
                                 const std::string& csv, const std::vector<double>& slips) {
  std::vector<WheelPoint> points;
  std::vector<std::size_t> rows;
  std::vector<std::string> notes;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const rigs::WheelResult& r = runs[i];
    if (!slips.empty() && std::find(slips.begin(), slips.end(), r.slip) == slips.end()) continue;
    if (const std::string why = rigs::unsteady_reason(r); !why.empty())
      notes.push_back(fmt::format("{}:{}: calibrated on although {}", csv, i + 2, why));
    points.push_back({r.slip, r.load, r.dbp, r.torque, r.sinkage, int(i) + 2});
    rows.push_back(i);
  }
  const PointLocator where = [csv, rows](std::size_t k, const std::string& column) {
    return fmt::format("{}:{}, column '{}'", csv, rows[k] + 2, column);
  };
  WheelData d = make_wheel_data(std::move(points), wheel_geometry(wheel, csv), csv, where);
  d.notes = notes;
  return d;
}

CalibrationData calibration_data(const BevameterCurves& curves, const std::string& dir) {
  // Row i of the curves is line i + 2 of the file the pipeline wrote them to (after its header).
  auto locator = [](const std::string& file) {
    return [file](std::size_t i, const std::string& column) {
      return fmt::format("{}:{}, column '{}'", file, i + 2, column);
    };
  };
  std::vector<PlatePoint> plate;
  for (std::size_t i = 0; i < curves.plate.size(); ++i) {
    const rigs::PlateRow& r = curves.plate[i];
    const auto phase = parse_plate_phase(r.phase);
    if (!phase)
      throw RunError(fmt::format("plate rig row {}: phase '{}' is not load, unload or reload", i + 1, r.phase));
    plate.push_back({r.radius, r.sinkage, r.force, *phase, int(i) + 2});
  }
  CalibrationData d{make_plate_data(std::move(plate), dir + "/plate.csv", locator(dir + "/plate.csv")), std::nullopt,
                    default_priors(), std::nullopt};
  if (!curves.shear.empty()) {
    std::vector<ShearPoint> shear;
    for (std::size_t i = 0; i < curves.shear.size(); ++i) {
      const rigs::ShearRow& r = curves.shear[i];
      shear.push_back({r.inner_radius, r.outer_radius, r.normal_load, r.torque, r.angle, false, int(i) + 2});
    }
    d.shear = make_shear_data(std::move(shear), dir + "/shear.csv", locator(dir + "/shear.csv"));
  }
  return d;
}

CalibrationOutcome run_calibration(const CalibrationData& data, const CalibrationSettings& s) {
  const auto t0 = std::chrono::steady_clock::now();
  validate(s);
  // Every input is checked before the output folder is touched.
  CalibrationProblem problem(data.plate, data.shear, data.priors, s.noise, data.wheel, s.annulus_law,
                             s.elastic_stiffness);
  for (const auto& note : problem.notes()) spdlog::warn("{}", note);
  if (problem.dim() == 0) throw InputError("every parameter is fixed (by the priors and the data); nothing to infer");
  if (s.correlated_noise) set_correlation_times(problem, s.seed);

  fs::create_directories(s.out_dir);
  const CalibrationOptions opt = sampler_options(data, s);
  spdlog::info("calibrating: {} plate points{}{}", problem.set(0).size(),
               data.shear ? fmt::format(", {} shear points", problem.set(1).size()) : std::string(", no shear data"),
               data.wheel ? fmt::format(", {} wheel rows (steady SCM wheel; S is fitted)", data.wheel->points.size())
                          : std::string());
  const CalibrationResult res = calibrate(problem, opt);
  for (const auto& note : res.notes) spdlog::warn("{}", note);

  remove_earlier_outputs(s.out_dir);
  const OutputContext ctx{sampler_name(s.sampler), s.seed, opt.warmup};
  CalibrationOutcome out{res.converged, {}, scm_params_json(problem, res, ctx)};
  out.fitted = lowfi::parse_scm_soil(out.params["Soil parameters"], "the calibrated set");
  if (out.params.contains("Slip sinkage"))
    out.fitted.slip_sinkage = lowfi::parse_slip_sinkage(out.params["Slip sinkage"], "the calibrated set");
  write_scm_params_json(s.out_dir + "/scm_params.json", out.params);
  const std::size_t nv = res.names.size();
  for (int c = 0; c < res.chains; ++c)
    for (std::size_t d : thinned_draws(res.draws, kPosteriorSets)) {
      Eigen::VectorXd x(res.num_params);
      for (int v = 0; v < res.num_params; ++v) x[v] = res.values[c][d * nv + v];
      out.posterior_sets.push_back(problem.soil_of(problem.expand(x)));
    }
  const InferenceData idata = make_inference_data(problem, res, s.seed);
  write_inference_data_h5(s.out_dir + "/posterior.h5", idata);
  const std::string report = summary_report(problem, res, ctx);
  write_text_atomically(s.out_dir + "/summary.txt", report);
  if (s.plots) {
    if (gnuplot_available())
      write_plots(s.out_dir, problem, res, idata);
    else
      spdlog::warn("gnuplot not found: no plots written (install gnuplot-nox; scripts/setup.sh does)");
  }
  fs::remove(opt.checkpoint_path);
  std::fputs(report.c_str(), stdout);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  spdlog::info("wrote {}/scm_params.json, posterior.h5, summary.txt{} in {:.2f} s", s.out_dir, s.plots ? ", plots" : "",
               seconds);
  if (!res.converged)
    spdlog::error("sampling did not converge ({}); the outputs are written but should not be trusted", res.termination);
  return out;
}

}  // namespace terracal::app
