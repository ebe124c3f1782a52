#include "bayes/calibration_outputs.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "bayes/plots.hpp"
#include "core/atomic_file.hpp"
#include "lowfi/slip_sinkage.hpp"

namespace terracal::bayes {
namespace {

using ordered_json = nlohmann::ordered_json;

// S is a parameter of the outputs only where wheel curves identified it (otherwise the set has no
// "Slip sinkage" block, as before wheel curves could be given); R and k_annulus only where the
// annulus had its own law.
bool reported(const CalibrationProblem& pb, int i) { return pb.reported(i); }

// The noise sd's key in scm_params.json: the type and its unit.
std::string noise_key(const ObservationSet& s) {
  if (s.name == "plate") return "plate_N";
  if (s.name == "shear") return "shear_Nm";
  return s.name + "_" + (s.unit == "N m" ? std::string("Nm") : s.unit);
}

// Index of parameter i among the result's free variables, or -1 if it is fixed.
int free_slot(const CalibrationProblem& pb, int i) {
  const auto& f = pb.free_indices();
  const auto it = std::find(f.begin(), f.end(), i);
  return it == f.end() ? -1 : static_cast<int>(it - f.begin());
}

double rms(const std::vector<double>& w) {
  double s = 0;
  for (double v : w) s += v * v;
  return w.empty() ? 0 : std::sqrt(s / double(w.size()));
}

// The data-unit noise sd of test type t: s_t times the rms weight (= s_t for absolute noise).
double noise_sd_in_units(const CalibrationProblem& pb, const CalibrationResult& res, int t) {
  return std::sqrt(res.point.noise_var[t]) * rms(pb.set(t).w);
}

constexpr const char* kElasticMethod = "weighted linear least squares on unload/reload branches";

// Ke is not sampled: its posterior entry is the normal approximation of the linear fit. The keys
// are those of the sampled entries; R-hat and bulk ESS describe Markov chains and are null here.
// Not fitted, it reads like a fixed parameter (value, sd 0, R-hat 1, ESS 0, "fixed": true).
ordered_json elastic_posterior(const ElasticFit& e) {
  if (!e.fitted)
    return {{"mean", e.ke},
            {"sd", 0.0},
            {"q05", e.ke},
            {"q50", e.ke},
            {"q95", e.ke},
            {"rhat", 1.0},
            {"ess_bulk", 0.0},
            {"fixed", true},
            {"method", "Chrono default: not fitted (no usable unload rows; see Fit.notes)"}};
  return {{"mean", e.ke},
          {"sd", e.sd},
          {"q05", e.quantile(0.05)},
          {"q50", e.quantile(0.5)},
          {"q95", e.quantile(0.95)},
          {"rhat", nullptr},
          {"ess_bulk", nullptr},
          {"method", std::string(kElasticMethod) + " (normal approximation)"}};
}

// Ke given by the caller: fixed at that value in the posterior, like a fixed parameter.
ordered_json given_elastic_posterior(double ke) {
  return {{"mean", ke},       {"sd", 0.0},        {"q05", ke},   {"q50", ke},
          {"q95", ke},        {"rhat", 1.0},      {"ess_bulk", 0.0}, {"fixed", true},
          {"method", "given (--elastic-stiffness); the plates' own fit is in Fit.elastic_stiffness"}};
}

ordered_json elastic_fit_block(const CalibrationProblem& pb) {
  const ElasticFit& e = pb.elastic();
  ordered_json b;
  if (pb.elastic_given()) {
    b["given_Pa_m"] = pb.set_elastic_stiffness();
    b["plates_fit_Pa_m"] = e.ke;
    b["used_by_set"] = "given";
  }
  b["fitted"] = e.fitted;
  b["method"] = e.fitted ? kElasticMethod : "not fitted: Chrono default";
  if (!e.fitted) return b;
  b["rows"] = e.rows;
  b["degrees_of_freedom"] = e.dof;
  b["residual_sd"] = e.noise_sd;
  b["lift_off_rows_excluded"] = e.lift_off_rows;
  ordered_json branches = ordered_json::array();
  for (const auto& br : e.branches)
    branches.push_back({{"plate_radius_m", br.radius},
                        {"phase", br.phase == PlatePhase::kUnload ? "unload" : "reload"},
                        {"first_line", br.first_line},
                        {"rows", br.rows},
                        {"plastic_sinkage_m", br.plastic_sinkage}});
  b["branches"] = branches;
  return b;
}

}  // namespace

nlohmann::ordered_json scm_params_json(const CalibrationProblem& pb, const CalibrationResult& res,
                                       const OutputContext& ctx) {
  ordered_json j;
  j["Type"] = "SCM";
  ordered_json soil;
  for (int i = 0; i < kSlipSinkage; ++i) soil[std::string(kChronoNames[i])] = res.point.map[i];
  soil["Elastic stiffness"] = pb.set_elastic_stiffness();
  soil["Damping"] = kDefaultDamping;
  j["Soil parameters"] = soil;
  if (pb.has_wheel()) j["Slip sinkage"] = lowfi::slip_sinkage_json({res.point.map[kSlipSinkage]});
  ordered_json post;
  for (int i = 0; i < kNumParams; ++i) {
    if (!reported(pb, i)) continue;
    const int v = free_slot(pb, i);
    if (v < 0) {
      const double x = pb.fixed_values()[i];
      post[std::string(kChronoNames[i])] = {{"mean", x}, {"sd", 0.0},   {"q05", x},        {"q50", x},
                                            {"q95", x},  {"rhat", 1.0}, {"ess_bulk", 0.0}, {"fixed", true}};
      continue;
    }
    const auto& s = res.summary[v];
    post[std::string(kChronoNames[i])] = {{"mean", s.mean}, {"sd", s.sd},     {"q05", s.q05},          {"q50", s.q50},
                                          {"q95", s.q95},   {"rhat", s.rhat}, {"ess_bulk", s.ess_bulk}};
  }
  post["Elastic stiffness"] =
      pb.elastic_given() ? given_elastic_posterior(pb.set_elastic_stiffness()) : elastic_posterior(pb.elastic());
  j["Posterior"] = post;
  ordered_json noise, relative;
  for (int t = 0; t < pb.num_types(); ++t) {
    noise[noise_key(pb.set(t))] = noise_sd_in_units(pb, res, t);
    if (!pb.set(t).is_wheel()) relative[pb.set(t).name] = std::sqrt(res.point.noise_var[t]);
  }
  ordered_json fit;
  fit["point_estimate"] = "MAP";
  fit["residual_sum_squares"] = res.point.weighted_rss;
  fit["noise_sd"] = noise;
  fit["noise_model"] = pb.noise_model() == NoiseModel::kRelative ? "relative" : "absolute";
  bool correlated = false;
  for (int t = 0; t < pb.num_types(); ++t) correlated = correlated || pb.correlation_time(t) > 1;
  if (correlated) {
    ordered_json tau;
    for (int t = 0; t < pb.num_types(); ++t) tau[pb.set(t).name] = pb.correlation_time(t);
    fit["noise_correlation"] = "ar1";
    fit["correlation_times"] = tau;
  }
  if (pb.has_wheel()) {
    fit["wheel_noise_model"] = "absolute";
    fit["wheel"] = {{"radius_m", pb.wheel().radius},
                    {"width_m", pb.wheel().width},
                    {"angular_velocity_rad_s", pb.wheel().angular_velocity},
                    {"model", "steady SCM wheel (lowfi/scm_steady_wheel.hpp), effects damping and slip_sinkage"}};
  }
  if (pb.annulus_scaled())
    fit["annulus_law"] = {{"law", "scaled"},
                          {"strength_ratio_R", res.point.map[kShearRatio]},
                          {"annulus_janosi_k_m", res.point.map[kAnnulusJanosi]},
                          {"meaning",
                           "the annulus's torque is the set's Mohr-Coulomb strength over R with its own Janosi k; "
                           "neither is part of the SCM set"}};
  if (pb.noise_model() == NoiseModel::kRelative) fit["noise_relative_sd"] = relative;
  fit["draws"] = res.draws;
  fit["chains"] = res.chains;
  fit["seed"] = ctx.seed;
  fit["sampler"] = ctx.sampler;
  fit["warmup"] = ctx.warmup;
  fit["converged"] = res.converged;
  fit["failed_evaluations"] = res.failed_evaluations;
  fit["elastic_stiffness"] = elastic_fit_block(pb);
  fit["damping"] = "Chrono default: not identified by quasi-static bevameter curves";
  std::vector<std::string> notes = pb.notes();
  notes.insert(notes.end(), res.notes.begin(), res.notes.end());
  fit["notes"] = notes;
  j["Fit"] = fit;
  return j;
}

void write_scm_params_json(const std::string& path, const nlohmann::ordered_json& params) {
  write_text_atomically(path, params.dump(2) + "\n");
}

InferenceData make_inference_data(const CalibrationProblem& pb, const CalibrationResult& res, std::uint64_t seed,
                                  int predictive_draws) {
  InferenceData id;
  Group posterior{"posterior", {}};
  for (std::size_t v = 0; v < res.names.size(); ++v) {
    const Chains ch = res.chains_of(static_cast<int>(v));
    const int i = v < static_cast<std::size_t>(res.num_params) ? pb.free_indices()[v] : -1;
    posterior.variables.push_back(chain_draw_variable(res.names[v], i >= 0 ? std::string(kUnits[i]) : "1", ch));
  }
  id.groups.push_back(posterior);

  id.groups.push_back(sample_stats_group(res.lp, res.accepted));

  Group observed{"observed_data", {}}, constant{"constant_data", {}}, predictive{"posterior_predictive", {}};
  Rng rng = Rng::for_stream(seed, 7);
  const auto keep = thinned_draws(res.draws, predictive_draws);
  for (int t = 0; t < pb.num_types(); ++t) {
    const ObservationSet& s = pb.set(t);
    const std::string obs_dim = s.name + "_obs";
    const std::string yname = s.name == "plate" ? "plate_force" : s.name == "shear" ? "shear_torque" : s.name;
    observed.variables.push_back({yname, {obs_dim}, {s.size()}, s.y, s.unit});
    if (s.name == "plate") {
      constant.variables.push_back({"plate_radius", {obs_dim}, {s.size()}, s.r, "m"});
      constant.variables.push_back({"plate_sinkage", {obs_dim}, {s.size()}, s.x_axis, "m"});
    } else if (s.is_wheel()) {
      constant.variables.push_back({s.name + "_load", {obs_dim}, {s.size()}, s.load, "N"});
      constant.variables.push_back({s.name + "_slip", {obs_dim}, {s.size()}, s.x_axis, "1"});
    } else {
      constant.variables.push_back({"shear_normal_load", {obs_dim}, {s.size()}, s.load, "N"});
      constant.variables.push_back({"shear_angle", {obs_dim}, {s.size()}, s.x_axis, "rad"});
    }
    // y_rep = f(theta) + s_t w_i eps for thinned posterior draws.
    Variable rep{
        yname, {"chain", "draw", obs_dim}, {static_cast<std::size_t>(res.chains), keep.size(), s.size()}, {}, s.unit};
    const int sigma_slot = res.num_params + t;
    const std::size_t nv = res.names.size();
    for (int c = 0; c < res.chains; ++c)
      for (std::size_t d : keep) {
        Eigen::VectorXd x(res.num_params);
        for (int v = 0; v < res.num_params; ++v) x[v] = res.values[c][d * nv + v];
        const double sd = std::sqrt(res.values[c][d * nv + sigma_slot]);
        const std::vector<double> f = pb.predict_all(t, pb.expand(x));
        for (std::size_t i = 0; i < s.size(); ++i) rep.data.push_back(f[i] + sd * s.w[i] * rng.normal());
      }
    predictive.variables.push_back(rep);
  }
  id.groups.push_back(observed);
  id.groups.push_back(constant);
  id.groups.push_back(predictive);
  return id;
}

std::vector<std::string> write_plots(const std::string& dir, const CalibrationProblem& pb, const CalibrationResult& res,
                                     const InferenceData& idata) {
  std::vector<std::string> written;
  const Group& pred = *std::find_if(idata.groups.begin(), idata.groups.end(),
                                    [](const Group& g) { return g.name == "posterior_predictive"; });
  for (int t = 0; t < pb.num_types(); ++t) {
    const ObservationSet& s = pb.set(t);
    const Variable& rep = pred.variables[t];
    const std::size_t samples = rep.shape[0] * rep.shape[1];
    const std::vector<double> fit = pb.predict_all(t, res.point.map);
    // One series per curve; developed shear rows (no angle) get their own plot against the load.
    std::vector<FitSeries> curves(s.curve_labels.size()), developed(1);
    developed[0].label = "fully developed torque";
    for (std::size_t i = 0; i < s.size(); ++i) {
      std::vector<double> col(samples);
      for (std::size_t k = 0; k < samples; ++k) col[k] = rep.data[k * s.size() + i];
      const bool is_developed = s.name == "shear" && s.angle[i] < 0;
      FitSeries& f = is_developed ? developed[0] : curves[s.curve[i]];
      f.x.push_back(is_developed ? s.load[i] : s.x_axis[i]);
      f.observed.push_back(s.y[i]);
      f.fit.push_back(fit[i]);
      f.lo.push_back(quantile(col, 0.025));
      f.hi.push_back(quantile(col, 0.975));
    }
    for (std::size_t c = 0; c < curves.size(); ++c) curves[c].label = s.curve_labels[c];
    std::erase_if(curves, [](const FitSeries& f) { return f.x.empty(); });
    const std::string png = dir + "/" + s.name + "_fit.png";
    if (s.name == "plate") {
      plot_fit(png, "Plate sinkage: data, MAP fit and 95 % posterior-predictive band", "sinkage z [m]", "force F [N]",
               curves);
    } else if (s.is_wheel()) {
      const std::string what = s.kind == ObservationSet::Kind::kWheelDbp      ? "drawbar pull [N]"
                               : s.kind == ObservationSet::Kind::kWheelTorque ? "torque [N m]"
                                                                              : "sinkage [m]";
      plot_fit(png, "Single wheel (steady SCM wheel): data, MAP fit and 95 % posterior-predictive band", "slip",
               what, curves);
    } else if (!curves.empty()) {
      plot_fit(png, "Annulus shear: data, MAP fit and 95 % posterior-predictive band", "shear angle [rad]",
               "torque [N m]", curves);
    }
    if (!curves.empty()) written.push_back(png);
    if (!developed[0].x.empty()) {
      const std::string dev = dir + "/shear_developed.png";
      plot_fit(dev, "Fully developed annulus torque", "normal load W [N]", "torque [N m]", developed);
      written.push_back(dev);
    }
  }
  // Pairwise marginals: one row per draw (all chains), one column per free parameter.
  std::vector<std::string> names;
  for (int v = 0; v < res.num_params; ++v)
    names.push_back(fmt::format("{} [{}]", res.names[v], kUnits[pb.free_indices()[v]]));
  std::vector<std::vector<double>> draws;
  const std::size_t nv = res.names.size();
  for (const auto& chain : res.values)
    for (long d = 0; d < res.draws; ++d)
      draws.emplace_back(chain.begin() + d * nv, chain.begin() + d * nv + res.num_params);
  plot_pairs(dir + "/pairs.png", names, draws);
  written.push_back(dir + "/pairs.png");
  return written;
}

std::string summary_report(const CalibrationProblem& pb, const CalibrationResult& res, const OutputContext& ctx) {
  std::string r = "terracal calibrate: summary\n";
  for (int t = 0; t < pb.num_types(); ++t)
    r += fmt::format("  data        {:<6} {} points in {} curves, noise model {}{}\n", pb.set(t).name, pb.set(t).size(),
                     pb.set(t).curve_labels.size(),
                     pb.noise_model() == NoiseModel::kRelative && !pb.set(t).is_wheel() ? "relative" : "absolute",
                     pb.correlation_time(t) > 1 ? fmt::format(", correlation time {:.3g} (counts as {:.3g} rows)",
                                                              pb.correlation_time(t), pb.effective_rows(t))
                                                : std::string());
  r += fmt::format("  stage 1     global search (NLopt CRS2 + BOBYQA): {} evaluations\n", res.point.global_evaluations);
  r += fmt::format("  stage 2     least squares (Ceres): {}\n", res.point.ceres_report);
  r += fmt::format("              covariance (DENSE_SVD): {}\n",
                   res.point.covariance_ok
                       ? "ok"
                       : fmt::format("{} direction(s) not constrained by the data, given a floor variance",
                                     res.point.unconstrained_directions));
  // (Whether the run resumed from a checkpoint is logged, not written: a resumed run's files are
  // byte-identical to an uninterrupted one's.)
  r += fmt::format(
      "  stage 3     MCMC {}: {} chains x {} draws after {} warm-up, acceptance {:.3f}, failed evaluations {}\n",
      ctx.sampler, res.chains, res.draws, ctx.warmup, res.acceptance_rate, res.failed_evaluations);
  r += fmt::format("  termination {}\n", res.termination);
  const ElasticFit& ke = pb.elastic();
  r +=
      ke.fitted
          ? fmt::format(
                "  elastic     Ke by weighted linear least squares (Eigen QR) on {} unload/reload rows in {} branches, "
                "{} dof:\n              a separate linear problem (one nuisance intercept, the plastic sinkage, per "
                "branch), "
                "not sampled;\n              quantiles from the normal approximation\n\n",
                ke.rows, ke.branches.size(), ke.dof)
          : "  elastic     Ke not fitted (no usable unload rows): Chrono's default\n\n";
  if (pb.elastic_given())
    r.insert(r.size() - 1, fmt::format("  elastic     the set's Ke is given (--elastic-stiffness {:g} Pa/m); the plates' "
                                       "fit ({:g} Pa/m) is reported only\n",
                                       pb.set_elastic_stiffness(), ke.ke));
  if (pb.annulus_scaled())
    r.insert(r.size() - 1,
             "  annulus     law scaled: the annulus's torque is the set's strength over R, with its own Janosi "
             "k_annulus;\n              R and k_annulus are not part of the SCM set\n");
  r += fmt::format("  {:<10} {:>13} {:>13} {:>12} {:>13} {:>13} {:>13} {:>7} {:>8}\n", "parameter", "MAP", "mean", "sd",
                   "5 %", "50 %", "95 %", "R-hat", "ESS");
  for (std::size_t v = 0; v < res.names.size(); ++v) {
    if (v == static_cast<std::size_t>(res.num_params) &&
        ke.fitted)  // after the SCM parameters; no R-hat/ESS: not sampled
      r += fmt::format("  {:<10} {:13.6g} {:13.6g} {:12.4g} {:13.6g} {:13.6g} {:13.6g} {:>7} {:>8}\n",
                       pb.elastic_given() ? "Ke plates" : "Ke", ke.ke,
                       ke.ke, ke.sd, ke.quantile(0.05), ke.quantile(0.5), ke.quantile(0.95), "-", "-");
    const auto& s = res.summary[v];
    const bool param = v < static_cast<std::size_t>(res.num_params);
    const std::string map = param ? fmt::format("{:13.6g}", res.point.map[pb.free_indices()[v]])
                                  : fmt::format("{:13.6g}", res.point.noise_var[v - res.num_params]);
    r += fmt::format("  {:<10} {} {:13.6g} {:12.4g} {:13.6g} {:13.6g} {:13.6g} {:7.4f} {:8.0f}\n", res.names[v], map,
                     s.mean, s.sd, s.q05, s.q50, s.q95, s.rhat, s.ess_bulk);
  }
  for (int i = 0; i < kNumParams; ++i)
    if (free_slot(pb, i) < 0 && reported(pb, i)) r += fmt::format("  {:<10} fixed at {:g}\n", kShortNames[i], pb.fixed_values()[i]);
  if (pb.elastic_given())
    r += fmt::format("  {:<10} fixed at {:g} (given by --elastic-stiffness: the set's)\n", "Ke", pb.set_elastic_stiffness());
  else if (!ke.fitted)
    r += fmt::format("  {:<10} fixed at {:g} (Chrono default, not fitted)\n", "Ke", ke.ke);
  for (const auto& n : pb.notes()) r += "  note: " + n + "\n";
  for (const auto& n : res.notes) r += "  note: " + n + "\n";
  return r;
}

}  // namespace terracal::bayes
