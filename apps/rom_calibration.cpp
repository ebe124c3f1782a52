#include "apps/rom_calibration.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "apps/report_plots.hpp"
#include "bayes/model_outputs.hpp"
#include "bayes/model_point_estimate.hpp"
#include "bayes/posterior_h5.hpp"
#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "core/json_file.hpp"
#include "core/text_check.hpp"
#include "rom/batch_vary.hpp"
#include "rom/rom_forward.hpp"
#include "rom/rom_vehicle_edit.hpp"
#include "rom/rom_vehicle_json.hpp"

namespace terracal::app {
namespace {

// The value a parameter has in `base` (a scale is 1 there).
double base_value(const rom::RomVehicle& v, const std::string& n) {
  if (n == "mass") return v.mass;
  if (n == "cg_height") return v.cg_height;
  if (n == "cg_to_front") return v.cg_to_front;
  if (n == "yaw_inertia") return v.yaw_inertia;
  if (n == "roll_inertia") return v.roll_inertia;
  if (n == "max_steer") return v.max_steer;
  if (n == "friction") return v.friction;
  if (n == "gravity") return v.gravity;
  if (n == "drag_area") return v.drag_area;
  if (n == "roll_stiffness_front") return v.roll_stiffness[0];
  if (n == "roll_stiffness_rear") return v.roll_stiffness[1];
  if (n == "roll_damping_front") return v.roll_damping[0];
  if (n == "roll_damping_rear") return v.roll_damping[1];
  if (n == "max_brake_torque") return v.powertrain.max_brake_torque;
  if (n == "rolling_resistance") return v.tire[0].rolling_resistance;
  if (n == "roll_stiffness_total") return v.roll_stiffness[0] + v.roll_stiffness[1];
  if (n == "roll_stiffness_front_share") return v.roll_stiffness[0] / (v.roll_stiffness[0] + v.roll_stiffness[1]);
  return 1.0;  // the scales
}

bayes::ModelParameter uniform(const rom::RomVehicle& base, const std::string& name, double lo, double hi) {
  bayes::ModelParameter p{name, rom::vary_parameter_unit(name), {}, base_value(base, name)};
  p.prior.lower = lo;
  p.prior.upper = hi;
  return p;
}

bool has_roll(rom::RomModel m) { return m == rom::RomModel::k18Dof; }

// The RMSE of each channel of one reference between two prediction vectors laid out as RomForward's.
double rmse(const std::vector<double>& a, const std::vector<double>& b, std::size_t from, std::size_t n) {
  double s = 0;
  for (std::size_t i = from; i < from + n; ++i) s += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(s / double(n));
}

// A tire scale's default prior: 0.2 to 5, but not below the smallest scale whose tire passes its
// checks (a tire curve that would start convex): a prior reaching into refused vehicles puts a cliff
// of failed runs inside the support, where least squares stops and proposals are wasted.
bayes::ModelParameter tire_scale(const rom::RomVehicle& b, const std::string& name) {
  return uniform(b, name, std::max(0.2, 1.001 * rom::smallest_valid_value(b, name)), 5);
}

}  // namespace

std::vector<bayes::ModelParameter> default_rom_parameters(rom::RomModel model, const rom::RomVehicle& b) {
  std::vector<bayes::ModelParameter> p = {tire_scale(b, "tire_cornering_scale_front"),
                                          tire_scale(b, "tire_cornering_scale_rear"),
                                          tire_scale(b, "tire_longitudinal_scale")};
  // The roll stiffness as its sum and front share: manoeuvres pin the sum far more tightly than the
  // split, and front and rear as parameters make a long diagonal ridge that chains cross slowly
  // (docs/decisions.md, "ROM calibration sampler").
  if (has_roll(model)) {
    for (const char* n : {"roll_stiffness_total", "roll_damping_front", "roll_damping_rear"})
      p.push_back(uniform(b, n, 0.25 * base_value(b, n), 4 * base_value(b, n)));
    p.push_back(uniform(b, "roll_stiffness_front_share", 0.05, 0.95));
  }
  p.push_back(uniform(b, "max_steer", 0.5 * b.max_steer, std::min(1.5 * b.max_steer, 1.5)));
  p.push_back(uniform(b, "torque_scale", 0.3, 3));
  if (b.has(rom::kEffectRollingResistance)) p.push_back(uniform(b, "rolling_resistance", 0, 0.1));
  if (b.has(rom::kEffectAeroDrag)) p.push_back(uniform(b, "drag_area", 0, std::max(10 * b.drag_area, 10.0)));
  return p;
}

std::vector<bayes::ModelParameter> read_rom_parameters(const std::string& path, rom::RomModel model,
                                                       const rom::RomVehicle& base,
                                                       std::vector<std::pair<std::string, double>>& fixed) {
  const nlohmann::json j = read_json_file(path, "parameters file");
  if (!j.is_object() || j.empty())
    throw InputError(fmt::format("{}: expected a JSON object keyed by parameter name, with at least one key", path));
  std::vector<std::string> names;  // the vehicle parameters (friction and gravity are run settings)
  for (const auto& n : rom::vary_parameter_names())
    if (!rom::is_run_setting(n)) names.push_back(n);
  std::vector<bayes::ModelParameter> out;
  for (const auto& [key, spec] : j.items()) {
    if (std::find(names.begin(), names.end(), key) == names.end())
      throw InputError(fmt::format("{}: unknown key {}; expected a vehicle parameter: {}", path, excerpt(key),
                                   fmt::join(names, ", ")));
    if (!has_roll(model) && key.rfind("roll_", 0) == 0)
      throw InputError(fmt::format("{}: key '{}': the {} model has no roll stiffness or damping", path, key,
                                   rom::model_name(model)));
    bayes::ModelParameter p{key, rom::vary_parameter_unit(key), {}, base_value(base, key)};
    p.prior = bayes::parse_prior(spec, path, key, rom::vary_parameter_range(key), p.prior);
    if (p.prior.fixed()) {
      fixed.emplace_back(key, p.prior.value);
      continue;
    }
    if (const double lowest = rom::smallest_valid_value(base, key); p.prior.lower < lowest)
      spdlog::warn("{}: key '{}': values below {:.4g} make tires that fail their checks (df0 < 2 fm / sm); the "
                   "prior's lower bound {} lets runs there fail, which slows the fit (give a lower bound of "
                   "at least {:.4g})",
                   path, key, lowest, p.prior.lower, 1.001 * lowest);
    if (!(p.prior.lower <= p.initial && p.initial <= p.prior.upper))
      p.initial = 0.5 * (p.prior.lower + p.prior.upper);  // the preset's value is outside: start in the middle
    out.push_back(p);
  }
  std::vector<std::string> given;
  for (const auto& [key, spec] : j.items()) given.push_back(key);
  if (const std::string overlap = rom::overlapping_parameters(given); !overlap.empty())
    throw InputError(fmt::format("{}: {}", path, overlap));
  if (out.empty()) throw InputError(fmt::format("{}: every parameter is fixed; nothing to fit", path));
  return out;
}

std::vector<bayes::ModelChannel> rom_channels(const std::vector<rom::RomReference>& refs, rom::RomModel model,
                                              std::vector<rom::RomChannel>& which) {
  which.clear();
  for (int c = 0; c < rom::kRomChannelCount; ++c) {
    const auto ch = static_cast<rom::RomChannel>(c);
    if (ch == rom::kRcRoll && model == rom::RomModel::k11Dof) continue;
    const bool everywhere = std::all_of(refs.begin(), refs.end(), [&](const auto& r) { return r.has[c]; });
    if (!everywhere && ch == rom::kRcRoll) continue;  // roll is optional; the others are required
    which.push_back(ch);
  }
  std::vector<bayes::ModelChannel> out;
  for (rom::RomChannel c : which) {
    bayes::ModelChannel m{rom::kRomChannelNames[c], rom::kRomChannelUnits[c], {}, {}, {}, {}};
    for (std::size_t k = 0; k < refs.size(); ++k) {
      m.y.insert(m.y.end(), refs[k].values[c].begin(), refs[k].values[c].end());
      m.x.insert(m.x.end(), refs[k].time.begin(), refs[k].time.end());
      m.curve.insert(m.curve.end(), refs[k].time.size(), static_cast<int>(k));
      m.curve_labels.push_back(refs[k].name);
    }
    out.push_back(std::move(m));
  }
  return out;
}

namespace {

// fit_<reference>.csv and .png: each channel's reference, preset-ROM and calibrated-ROM values.
void write_fits(const RomCalibrationSettings& s, const std::vector<rom::RomReference>& refs,
                const std::vector<rom::RomChannel>& which, const std::vector<double>& preset,
                const std::vector<double>& map, nlohmann::ordered_json& rmse_json) {
  std::size_t total = 0;
  for (const auto& r : refs) total += r.time.size();
  std::size_t first = 0;
  for (const auto& r : refs) {
    std::string csv = "time";
    for (rom::RomChannel c : which)
      csv += fmt::format(",{0}_reference,{0}_preset,{0}_calibrated", rom::kRomChannelNames[c]);
    csv += "\n";
    for (std::size_t i = 0; i < r.time.size(); ++i) {
      csv += fmt::format("{:.9g}", r.time[i]);
      for (std::size_t k = 0; k < which.size(); ++k) {
        const std::size_t at = k * total + first + i;
        csv += fmt::format(",{:.9g},{:.9g},{:.9g}", r.values[which[k]][i], preset[at], map[at]);
      }
      csv += "\n";
    }
    const std::string name = "fit_" + r.name;
    write_text_atomically(s.out + "/" + name + ".csv", csv);
    nlohmann::ordered_json e;
    std::vector<std::pair<std::string, std::string>> panels;
    for (std::size_t k = 0; k < which.size(); ++k) {
      std::vector<double> y(r.values[which[k]].begin(), r.values[which[k]].end());
      std::vector<double> yp(preset.begin() + k * total + first, preset.begin() + k * total + first + r.time.size());
      std::vector<double> ym(map.begin() + k * total + first, map.begin() + k * total + first + r.time.size());
      e[rom::kRomChannelNames[which[k]]] = {{"preset", rmse(y, yp, 0, y.size())},
                                            {"calibrated", rmse(y, ym, 0, y.size())}};
      panels.emplace_back(rom::kRomChannelNames[which[k]], rom::kRomChannelUnits[which[k]]);
    }
    rmse_json[r.name] = e;
    if (s.plots)
      plot_rom_fit(s.out, name + ".csv", name + ".png",
                   fmt::format("{}: reference and {} ROM", r.name, rom::model_name(s.model)), panels);
    first += r.time.size();
  }
}

// i-SIR on a GPU: as many steps' proposals per batch as one launch holds at once. A launch lasts about
// one run's time up to the GPU's capacity (one thread per run past one wave of four-lane vehicles),
// so the steps cost little more than one (docs/decisions.md, "ROM calibration on a GPU"). 1 elsewhere:
// CPU threads take as long for a step's runs in one batch as in two.
int auto_lookahead(const RomCalibrationSettings& s, const bayes::CalibrationOptions& o, std::size_t references) {
  if (o.tries < 2 || s.device != rom::BatchDevice::kCuda) return 1;
  const long per_step = long(o.chains) * (o.tries - 1) * long(references);
  return int(std::clamp<long>(rom::gpu_batch_capacity(s.model) / std::max(per_step, 1L), 1, 64));
}

}  // namespace

RomCalibrationOutcome run_rom_calibration(const RomCalibrationSettings& s) {
  const auto start = std::chrono::steady_clock::now();
  rom::RomVehicle base = rom::load_rom_vehicle(s.vehicle);
  rom::check_model_effects(base, s.model);
  std::vector<std::pair<std::string, double>> fixed;
  std::vector<bayes::ModelParameter> params = s.params_json.empty()
                                                  ? default_rom_parameters(s.model, base)
                                                  : read_rom_parameters(s.params_json, s.model, base, fixed);
  for (const auto& [n, v] : fixed) rom::apply_vary_parameter(base, base, n, v);
  std::vector<rom::RomReference> refs;
  for (const auto& d : s.references) refs.push_back(rom::read_rom_reference(d));
  std::vector<rom::RomChannel> which;
  std::vector<bayes::ModelChannel> channels = rom_channels(refs, s.model, which);

  RomCalibrationOutcome out;
  for (const auto& p : params) out.parameters.push_back(p.name);
  const rom::RomForward forward({base, s.model, out.parameters, which, &refs, s.step, s.device});
  const auto batch = [&](const std::vector<Eigen::VectorXd>& xs, std::vector<std::vector<double>>& f) {
    std::vector<std::vector<double>> ps;
    for (const auto& x : xs) ps.emplace_back(x.data(), x.data() + x.size());
    forward(ps, f);
  };
  bayes::ModelProblem pb(params, channels, batch);
  // On a GPU the samplers' batches compare where they run: a launch of 8,064 runs then copies 4 sums
  // per run back instead of about 270 MB of samples. The CPU keeps the predictions (and the sums
  // of sse_of).
  if (s.device == rom::BatchDevice::kCuda)
    pb.set_batch_sse([&](const std::vector<Eigen::VectorXd>& xs, std::vector<std::vector<double>>& sums) {
      std::vector<std::vector<double>> ps;
      for (const auto& x : xs) ps.emplace_back(x.data(), x.data() + x.size());
      forward.sse(ps, sums);
    });
  std::vector<std::string> channel_names;
  for (const auto& c : channels) channel_names.push_back(c.name);
  spdlog::info("calibrate-rom: {} parameters ({}); channels {}; {} references", pb.dim(),
               fmt::join(out.parameters, ", "), fmt::join(channel_names, ", "), refs.size());

  bayes::CalibrationResult& res = out.result;
  const bayes::ModelPointOptions po{.seed = s.seed, .global_points = s.global_points, .starts = s.starts};
  res.point = bayes::estimate_model_point(pb, po);
  if (s.correlated_noise) {
    pb.set_correlation_times(pb.correlation_times(res.point.x));
    bayes::laplace_covariance(pb, po, res.point);  // the width the correlated likelihood has
    std::string taus;
    for (int c = 0; c < pb.num_channels(); ++c)
      taus += fmt::format("{}{} {:.3g}", c ? ", " : "", channels[c].name, pb.correlation_time(c));
    spdlog::info("calibrate-rom: residual correlation times (rows per independent one): {}", taus);
  }
  std::string at;
  for (int j = 0; j < pb.dim(); ++j)
    at += fmt::format("{}{} = {:.4g} +- {:.2g}", j ? ", " : "", out.parameters[j], res.point.x[j],
                      std::sqrt(res.point.covariance(j, j)));
  spdlog::info("calibrate-rom: point estimate after {} runs: {} ({})", pb.runs(), at, res.point.ceres_report);
  if (res.point.start_objectives.size() > 1)
    spdlog::info(
        "calibrate-rom: least squares from {} starts (the vehicle's own values first, then the global "
        "search's best) ended at {:.6g} (the posterior with the noise profiled out, negated); kept start {}",
        res.point.start_objectives.size(), fmt::join(res.point.start_objectives, ", "), res.point.start + 1);
  res.names = out.parameters;
  res.num_params = pb.dim();
  for (const auto& c : channels) res.names.push_back("sigma2_" + c.name);
  bayes::CalibrationOptions o;
  o.seed = s.seed;
  o.sampler = s.sampler;
  const bool independence = s.sampler == bayes::SamplerKind::kIndependence;
  // i-SIR on a GPU: 96 points per chain and step. A chain on a point the proposal under-weights stays
  // there for fewer steps than with 64, which shortens the slow seeds' runs; H200, seeds 1-12: mean
  // 10.8 s, longest 17.4 s, against 10.7 s and 21.1 s (docs/decisions.md, "ROM calibration on a GPU").
  o.tries = !independence ? 1 : s.tries > 0 ? s.tries : s.device == rom::BatchDevice::kCuda ? 96 : 1;
  // i-SIR: 24 chains. With 64 tries a GPU launch then held 5 steps' proposals (lookahead) instead of 4
  // with 32 chains; H200, seeds 1-8 of the pipeline-rom references: 9.0-13.0 s against 10.6-20.3 s
  // (docs/decisions.md, "ROM calibration on a GPU"). With 96 tries it holds 3.
  o.chains = s.chains > 0 ? s.chains : !independence ? 2 * (pb.dim() + 1) : o.tries > 1 ? 24 : 4;
  o.lookahead = s.lookahead > 0 ? s.lookahead : independence ? auto_lookahead(s, o, refs.size()) : 1;
  o.min_ess = s.min_ess;
  o.max_rhat = s.max_rhat;
  // i-SIR moves in 92-95 % of its steps, so a chain leaves its dispersed start within a step or two:
  // 4 steps of warm-up instead of 10 took 3-4 s off a 40 s run on a GPU with the same R-hat
  // (docs/decisions.md, "ROM calibration on a GPU").
  o.warmup = s.warmup >= 0 ? s.warmup : o.tries > 1 ? 4 : 40;
  // Importance sampling goes on until its weights hold 300 effective points: a 10-parameter t fitted
  // to the 50-150 that the first round at the posterior's own weights keeps on 256-point CPU rounds
  // is a noisy proposal, on which chains stick. Dev VM (three starts), seeds 1 / 2 / 3: 94 / - / 161 s
  // -> 82 / 86 / 91 s; 600 was no faster (docs/decisions.md, "ROM calibration sampler"). A GPU's
  // rounds of 2,016 points stop above this anyway.
  o.adaptation_final_ess = 300;
  if (o.tries > 1) {
    // No random-walk move: a second launch per step, and on the full-vehicle references it did not
    // shorten the runs (seed 1: 55 against 60 s; seed 3: 82 against 65 s; docs/decisions.md,
    // "ROM calibration on a GPU"). Importance sampling fills a step's batch per round.
    o.local_moves = false;
    o.adaptation_points = std::max(o.adaptation_points, o.chains * (o.tries - 1));
  }
  // Delayed acceptance for the random-walk move: a move the surrogate rules out costs no run. Dev VM,
  // seeds 1 / 4 / 5 / 6: 10,147 / 18,714 / 10,091 / 10,596 runs -> 7,835 / 12,099 / 6,948 / 8,609
  // (docs/decisions.md, "Delayed acceptance").
  o.delayed_acceptance = s.delayed_acceptance > 0 || (s.delayed_acceptance < 0 && independence && o.local_moves);
  // Convergence checks at fixed intervals (calibrate-rom writes no checkpoint, and a check costs about
  // a millisecond): every 25 steps on the CPU (about a second of runs on 2 cores), after every i-SIR
  // step on a GPU (a launch of a few hundred ms). Blocks growing with the chain ran up to a quarter
  // past convergence.
  o.block = s.sampler == bayes::SamplerKind::kEnsemble           ? 200
            : o.tries > 1 && s.device == rom::BatchDevice::kCuda ? 1
                                                                 : 25;
  o.growing_blocks = s.sampler == bayes::SamplerKind::kEnsemble;
  o.max_draws = s.max_draws;
  o.progress = [&](const bayes::CalibrationProgress& p) {
    if (p.stage == "adapted") spdlog::info("calibrate-rom: proposal adapted to the posterior: {}", p.message);
    if (p.stage == "sampling" && p.draws_per_chain % 10 == 0)
      spdlog::info("calibrate-rom: {} draws per walker, max R-hat {:.4f}, min bulk ESS {:.0f} ({} runs so far)",
                   p.draws_per_chain, p.max_rhat, p.min_ess, pb.runs());
  };
  bayes::sample_posterior(pb.target(), o, res);
  spdlog::info("calibrate-rom: {} ({} chains, {} per step{}{}; acceptance rate {:.3g})", res.termination, o.chains,
               o.tries > 1 ? fmt::format("i-SIR with {} tries", o.tries) : std::string("Metropolis-Hastings"),
               o.lookahead > 1 ? fmt::format(", the proposals of {} steps per batch", o.lookahead) : "",
               o.delayed_acceptance ? ", random-walk moves with delayed acceptance" : "", res.acceptance_rate);
  out.runs = pb.runs();
  out.failed_runs = pb.failed_runs();
  out.forward_seconds = forward.stats().wall_seconds;
  out.stepping_seconds = forward.stats().stepping_seconds;
  out.model_seconds = forward.stats().call_seconds;

  // Outputs: the preset and the MAP vehicle run once more for the fits.
  std::vector<Eigen::VectorXd> two(2, Eigen::VectorXd(pb.dim()));
  for (int j = 0; j < pb.dim(); ++j) two[0][j] = params[j].initial;
  two[1] = res.point.x;
  const auto f = pb.predict(two);
  std::vector<std::string> names = out.parameters;
  std::vector<double> values(res.point.x.data(), res.point.x.data() + pb.dim());
  for (const auto& [n, v] : fixed) {
    names.push_back(n);
    values.push_back(v);
  }
  nlohmann::ordered_json j = rom::vehicle_json_with(s.vehicle, names, values);
  j["name"] = fmt::format("{} ({} calibrated)", j.value("name", s.vehicle), rom::model_name(s.model));
  nlohmann::ordered_json rmse_json;
  if (!f[0].empty() && !f[1].empty()) write_fits(s, refs, which, f[0], f[1], rmse_json);
  j["Posterior"] = bayes::model_posterior_json(pb, res);
  nlohmann::ordered_json fixed_json = nlohmann::ordered_json::object();
  for (const auto& [n, v] : fixed) fixed_json[n] = v;
  nlohmann::ordered_json noise, tau;
  for (int c = 0; c < pb.num_channels(); ++c) {
    noise[channels[c].name] = std::sqrt(res.point.noise_var[c]);
    tau[channels[c].name] = pb.correlation_time(c);
  }
  out.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  j["Fit"] = {{"model", rom::model_name(s.model)},
              {"vehicle", rom::rom_preset_json(s.vehicle).empty()
                              ? std::filesystem::absolute(s.vehicle).lexically_normal().string()
                              : s.vehicle},
              {"step", s.step},
              {"references", s.references},
              {"point_estimate", "MAP"},
              {"fixed", fixed_json},
              {"noise_sd", noise},
              {"noise_model", s.correlated_noise ? "correlated" : "white"},
              {"correlation_time", tau},
              {"rmse", rmse_json},
              {"sampler", s.sampler == bayes::SamplerKind::kEnsemble ? "ensemble" : "independence"},
              {"chains", res.chains},
              {"tries", o.tries},
              {"lookahead", o.lookahead},
              {"delayed_acceptance", o.delayed_acceptance},
              {"draws", res.draws},
              {"seed", s.seed},
              {"converged", res.converged},
              {"termination", res.termination},
              {"runs", out.runs},
              {"failed_runs", out.failed_runs},
              {"device", s.device == rom::BatchDevice::kCuda ? "cuda" : "cpu"},
              {"wall_seconds", out.wall_seconds}};
  write_text_atomically(s.out + "/rom_params.json", j.dump(2) + "\n");
  // About 320 predictive draws in all, whatever the number of chains (50 per chain of 32 chains made
  // the HMMWV's four references a 30 MB file).
  const int predictive = std::max(1, 320 / std::max(res.chains, 1));
  bayes::write_inference_data_h5(s.out + "/posterior.h5",
                                 bayes::make_model_inference_data(pb, res, s.seed, predictive));
  return out;
}

}  // namespace terracal::app
