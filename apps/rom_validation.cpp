#include "apps/rom_validation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <nlohmann/json.hpp>

#include "apps/rom_choices.hpp"
#include "bayes/diagnostics.hpp"
#include "bayes/posterior_h5.hpp"
#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "core/gnuplot.hpp"
#include "core/json_file.hpp"
#include "core/rng.hpp"
#include "rom/batch_vary.hpp"
#include "rom/rom_forward.hpp"
#include "rom/rom_vehicle_json.hpp"

namespace terracal::app {
namespace {

namespace fs = std::filesystem;
const double kNaN = std::numeric_limits<double>::quiet_NaN();

// What validate-rom takes from calibrate-rom's folder.
struct Posterior {
  rom::RomModel model = rom::RomModel::k18Dof;
  std::string vehicle;
  std::vector<std::pair<std::string, double>> fixed;
  std::uint64_t seed = 1;
  double step = 1e-3;
  std::vector<std::string> names;  // the fitted parameters
  std::vector<double> map;
  nlohmann::json summary;  // the "Posterior" block
  std::vector<rom::RomChannel> channels;
  std::size_t chains = 0, draws = 0;
  std::vector<const std::vector<double>*> values;  // [parameter] -> [chain * draws + draw]
  std::vector<const std::vector<double>*> sigma2;  // [channel] -> the same
  bayes::InferenceData idata;
};

// o[key], which `is` must accept; else an InputError naming `where`, the key and what was expected.
const nlohmann::json& member(const nlohmann::json& o, const std::string& key, const std::string& where,
                             const std::string& expected, bool (nlohmann::json::*is)() const noexcept) {
  const auto it = o.find(key);
  if (it == o.end() || !((*it).*is)())
    throw InputError(fmt::format("{} \"{}\": {}; expected {} (is this an output folder of calibrate-rom?)", where, key,
                                 it == o.end() ? "missing" : "of the wrong type", expected));
  return *it;
}

std::vector<std::string> channel_names(const std::vector<rom::RomChannel>& cs) {
  std::vector<std::string> n;
  for (auto c : cs) n.emplace_back(rom::kRomChannelNames[c]);
  return n;
}

void read_params_json(const std::string& path, Posterior& p) {
  if (!fs::is_regular_file(path))
    throw InputError(fmt::format("{}: not found; expected the rom_params.json that calibrate-rom writes", path));
  const nlohmann::json j = read_json_file(path, "calibrate-rom parameters file");
  if (!j.is_object()) throw InputError(fmt::format("{}: expected a JSON object with \"Fit\" and \"Posterior\"", path));
  const auto& fit = member(j, "Fit", path, "an object (calibrate-rom's \"Fit\" block)", &nlohmann::json::is_object);
  const auto& post =
      member(j, "Posterior", path, "an object (calibrate-rom's \"Posterior\" block)", &nlohmann::json::is_object);
  const std::string at = path + " \"Fit\"";
  const auto model = member(fit, "model", at, "11dof, 18dof or 24dof", &nlohmann::json::is_string).get<std::string>();
  const auto m = kRomModels.find(model);
  if (m == kRomModels.end())
    throw InputError(fmt::format("{} \"model\": '{}'; expected 11dof, 18dof or 24dof", at, model));
  p.model = m->second;
  p.vehicle = member(fit, "vehicle", at, "the calibrated vehicle (preset or file)", &nlohmann::json::is_string)
                  .get<std::string>();
  if (fit.contains("seed"))
    p.seed = member(fit, "seed", at, "a whole number", &nlohmann::json::is_number_unsigned).get<std::uint64_t>();
  if (fit.contains("step")) {
    p.step = member(fit, "step", at, "the ROM's step [s]", &nlohmann::json::is_number).get<double>();
    if (!(p.step >= 1e-5 && p.step <= 0.01))
      throw InputError(fmt::format("{} \"step\": {}; expected in [1e-05, 0.01]", at, p.step));
  }
  if (fit.contains("fixed")) {  // {"name": value} or [["name", value], ...]
    const auto& f = fit["fixed"];
    const auto add = [&](const nlohmann::json& k, const nlohmann::json& v) {
      if (!k.is_string() || !v.is_number())
        throw InputError(fmt::format("{} \"fixed\": expected parameter names with numbers", at));
      p.fixed.emplace_back(k.get<std::string>(), v.get<double>());
    };
    if (f.is_object())
      for (const auto& [k, v] : f.items()) add(k, v);
    else if (f.is_array())
      for (const auto& e : f) {
        if (!e.is_array() || e.size() != 2)
          throw InputError(fmt::format("{} \"fixed\": expected name-value pairs", at));
        add(e[0], e[1]);
      }
    else
      throw InputError(fmt::format("{} \"fixed\": expected an object of parameter names and values", at));
  }
  for (const auto& [name, e] : post.items()) {
    if (name.starts_with("sigma2_")) continue;
    if (!e.is_object() || !e.contains("map") || !e["map"].is_number())
      throw InputError(fmt::format("{} \"Posterior\" \"{}\": expected an object with the number \"map\"", path, name));
    p.names.push_back(name);
    p.map.push_back(e["map"].get<double>());
  }
  if (p.names.empty()) throw InputError(fmt::format("{} \"Posterior\": no fitted parameter", path));
  p.summary = post;
}

void read_posterior_h5(const std::string& path, Posterior& p) {
  if (!fs::is_regular_file(path))
    throw InputError(fmt::format("{}: not found; expected the posterior.h5 that calibrate-rom writes", path));
  try {
    p.idata = bayes::read_inference_data_h5(path);
  } catch (const std::exception& e) {
    throw InputError(fmt::format("{}: not a posterior file of calibrate-rom ({})", path, e.what()));
  }
  const bayes::Group* g = nullptr;
  for (const auto& grp : p.idata.groups)
    if (grp.name == "posterior") g = &grp;
  if (!g) throw InputError(fmt::format("{}: no group 'posterior'; expected calibrate-rom's posterior draws", path));
  std::map<std::string, const bayes::Variable*> vars;
  for (const auto& v : g->variables) {
    if (v.dims != std::vector<std::string>{"chain", "draw"} || v.shape.size() != 2 || v.shape[0] * v.shape[1] == 0 ||
        v.data.size() != v.shape[0] * v.shape[1])
      throw InputError(fmt::format("{}: posterior/{}: expected a (chain, draw) array", path, v.name));
    if (vars.empty()) p.chains = v.shape[0], p.draws = v.shape[1];
    if (v.shape[0] != p.chains || v.shape[1] != p.draws)
      throw InputError(fmt::format("{}: posterior/{}: {} x {} draws; expected {} x {} like the others", path, v.name,
                                   v.shape[0], v.shape[1], p.chains, p.draws));
    vars[v.name] = &v;
  }
  for (const auto& n : p.names) {
    const auto it = vars.find(n);
    if (it == vars.end())
      throw InputError(fmt::format("{}: no variable posterior/{}, a parameter of rom_params.json", path, n));
    p.values.push_back(&it->second->data);
  }
  for (const auto& [name, v] : vars) {
    if (!name.starts_with("sigma2_")) {
      if (std::find(p.names.begin(), p.names.end(), name) == p.names.end())
        throw InputError(fmt::format(
            "{}: posterior/{}: not a parameter of rom_params.json (files of two calibrations?)", path, name));
      continue;
    }
    const std::string ch = name.substr(7);
    const auto* c = std::find(std::begin(rom::kRomChannelNames), std::end(rom::kRomChannelNames), ch);
    if (c == std::end(rom::kRomChannelNames))
      throw InputError(
          fmt::format("{}: posterior/{}: unknown channel '{}'; expected vx, yaw_rate, roll or ay", path, name, ch));
    if (*c == std::string("roll") && p.model == rom::RomModel::k11Dof)
      throw InputError(fmt::format("{}: posterior/{}: the 11dof model has no roll", path, name));
    p.channels.push_back(static_cast<rom::RomChannel>(c - std::begin(rom::kRomChannelNames)));
  }
  if (p.channels.empty())
    throw InputError(fmt::format("{}: no posterior/sigma2_<channel>; expected the noise variances", path));
  std::sort(p.channels.begin(), p.channels.end());
  for (auto c : p.channels) p.sigma2.push_back(&vars.at(std::string("sigma2_") + rom::kRomChannelNames[c])->data);
}

double rmse(const std::vector<double>& a, const std::vector<double>& b) {
  if (b.empty()) return kNaN;
  double s = 0;
  for (std::size_t i = 0; i < a.size(); ++i) s += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(s / double(a.size()));
}

double coverage(const std::vector<double>& y, const std::vector<double>& lo, const std::vector<double>& hi) {
  std::size_t in = 0;
  for (std::size_t i = 0; i < y.size(); ++i) in += lo[i] <= y[i] && y[i] <= hi[i];
  return double(in) / double(y.size());
}

// One channel's rows of a RomForward prediction (empty stays empty).
std::vector<double> rows_of(const std::vector<double>& f, std::size_t c, std::size_t rows) {
  if (f.empty()) return {};
  return {f.begin() + c * rows, f.begin() + (c + 1) * rows};
}

// q05, q50, q95 of every (channel, row) over the draws that ran.
void quantiles(const std::vector<std::vector<double>>& f, std::size_t c, std::size_t rows, std::vector<double>* q05,
               std::vector<double>* q50, std::vector<double>* q95) {
  std::vector<double> col;
  for (std::size_t i = 0; i < rows; ++i) {
    col.clear();
    for (const auto& d : f)
      if (!d.empty()) col.push_back(d[c * rows + i]);
    if (q05) q05->push_back(bayes::quantile(col, 0.05));
    if (q50) q50->push_back(bayes::quantile(col, 0.5));
    if (q95) q95->push_back(bayes::quantile(col, 0.95));
  }
}

std::string csv_band(const RomReferenceValidation& r) {
  std::string s = "time";
  for (const auto& c : r.channels)
    s += fmt::format(",{0}_reference,{0}_map,{0}_median,{0}_q05,{0}_q95,{0}_pred_q05,{0}_pred_q95",
                     rom::kRomChannelNames[c.channel]);
  s += "\n";
  const auto num = [](const std::vector<double>& v, std::size_t i) {
    return v.empty() ? std::string("nan") : fmt::format("{:.12g}", v[i]);
  };
  for (std::size_t i = 0; i < r.time.size(); ++i) {
    s += fmt::format("{:.9g}", r.time[i]);
    for (const auto& c : r.channels)
      s += fmt::format(",{},{},{},{},{},{},{}", num(c.reference, i), num(c.map, i), num(c.median, i), num(c.q05, i),
                       num(c.q95, i), num(c.pred_q05, i), num(c.pred_q95, i));
    s += "\n";
  }
  return s;
}

// band_<reference>.png from band_<reference>.csv (the style of plot_rom_fit, apps/report_plots.cpp).
void plot_band(const std::string& dir, const RomReferenceValidation& r, const std::string& model) {
  const std::string name = "band_" + r.name;
  if (!gnuplot_available()) {
    spdlog::warn("gnuplot not found: {}.png not drawn", name);
    return;
  }
  const std::string work = dir + "/.plot_" + name;
  fs::create_directories(work);
  fs::copy_file(dir + "/" + name + ".csv", work + "/band.csv", fs::copy_options::overwrite_existing);
  const std::size_t n = r.channels.size(), rows = (n + 1) / 2;
  std::string s = fmt::format(
      "set terminal pngcairo noenhanced size 1400,{} font 'Sans,11'\nset output '{}.png'\n"
      "set datafile separator ','\nset grid\nset key below horizontal\nset xlabel 'time [s]'\n"
      "set style fill transparent solid 0.25 noborder\nset multiplot layout {},2 title '{}: {} ROM, posterior "
      "predictive'\n",
      450 * rows, name, rows, r.name, model);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t c = 2 + 7 * k;
    s += fmt::format(
        "set title '{0}'\nset ylabel '[{1}]'\nplot 'band.csv' using 1:{6}:{7} with filledcurves lc rgb '#1f77b4' "
        "title '90 % predictive (with noise)', '' using 1:{4}:{5} with filledcurves lc rgb '#d62728' title '90 % "
        "model band', '' using 1:{2} with lines lw 3 lc rgb 'black' title 'reference', '' using 1:{3} with lines lw 2 "
        "lc rgb 'red' title 'MAP ROM'\n",
        rom::kRomChannelNames[r.channels[k].channel], rom::kRomChannelUnits[r.channels[k].channel], c, c + 1, c + 3,
        c + 4, c + 5, c + 6);
  }
  s += "unset multiplot\n";
  try {
    run_gnuplot(s, work);
    if (fs::exists(work + "/" + name + ".png")) commit_file(work + "/" + name + ".png", dir + "/" + name + ".png");
  } catch (const RunError& e) {
    spdlog::warn("{}.png not drawn: {}", name, e.what());
  }
  std::error_code ec;
  fs::remove_all(work, ec);
}

std::string num(double v, const char* f = "{:.4g}") {
  return std::isnan(v) ? "failed" : fmt::format(fmt::runtime(f), v);
}
nlohmann::ordered_json jnum(double v) {
  return std::isnan(v) ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(v);
}

struct Pooled {
  double sq_map = 0, sq_median = 0, sq_preset = 0, in_model = 0, in_pred = 0, rows = 0;
};

void write_outputs(const RomValidationOutcome& o, const std::string& posterior, const nlohmann::json& summary) {
  std::string md = fmt::format(
      "# ROM validation: posterior-predictive runs\n\n"
      "- Posterior: `{}` ({} model, vehicle `{}`)\n"
      "- Draws: {} (chain, draw) pairs, uniformly with replacement from the posterior's {}; seed {}\n"
      "- Device: {}; step {} s; failed runs: {} (left out of the quantiles)\n"
      "- Batch wall time: {:.3g} s in all; command wall time {:.3g} s\n\n"
      "The **model band** is the 5-95 % range of the ROM's predictions over the draws, without observation noise: "
      "the ROM's parameter uncertainty alone. The **predictive band** adds to each draw's prediction normal noise "
      "of that draw's variance sigma2_<channel>: a calibrated model covers about 90 % of the reference samples "
      "with it; the model band is expected to cover fewer.\n\n",
      posterior, o.model, o.vehicle, o.draws, o.available_draws, o.seed, o.device, o.step, o.failed_runs,
      o.batch_seconds, o.wall_seconds);
  md += "## Parameters\n\n| parameter | MAP | q05 | q95 |\n|---|---|---|---|\n";
  for (const auto& n : o.parameters) {
    const auto& e = summary[n];
    const auto get = [&](const char* k) { return e.contains(k) && e[k].is_number() ? e[k].get<double>() : kNaN; };
    md += fmt::format("| {} | {} | {} | {} |\n", n, num(get("map")), num(get("q05")), num(get("q95")));
  }
  md +=
      "\n## Per reference\n\n| reference | channel | RMSE MAP | RMSE median | RMSE preset | coverage predictive 90 % "
      "(with noise) | coverage model band (no noise) |\n|---|---|---|---|---|---|---|\n";
  nlohmann::ordered_json refs = nlohmann::ordered_json::array();
  std::vector<Pooled> pool(o.channels.size());
  for (const auto& r : o.references) {
    nlohmann::ordered_json ch;
    for (std::size_t k = 0; k < r.channels.size(); ++k) {
      const auto& c = r.channels[k];
      const std::string unit = rom::kRomChannelUnits[c.channel];
      md += fmt::format("| {} | {} [{}] | {} | {} | {} | {:.1f} % | {:.1f} % |\n", r.name,
                        rom::kRomChannelNames[c.channel], unit, num(c.rmse_map), num(c.rmse_median), num(c.rmse_preset),
                        100 * c.coverage_predictive, 100 * c.coverage_model);
      ch[rom::kRomChannelNames[c.channel]] = {{"unit", unit},
                                              {"rmse_map", jnum(c.rmse_map)},
                                              {"rmse_median", jnum(c.rmse_median)},
                                              {"rmse_preset", jnum(c.rmse_preset)},
                                              {"coverage_predictive_90", c.coverage_predictive},
                                              {"coverage_model_90", c.coverage_model}};
      const double n = double(r.time.size());
      pool[k].sq_map += n * c.rmse_map * c.rmse_map;
      pool[k].sq_median += n * c.rmse_median * c.rmse_median;
      pool[k].sq_preset += n * c.rmse_preset * c.rmse_preset;
      pool[k].in_model += n * c.coverage_model;
      pool[k].in_pred += n * c.coverage_predictive;
      pool[k].rows += n;
    }
    refs.push_back({{"name", r.name},
                    {"dir", r.dir},
                    {"rows", r.time.size()},
                    {"wall_seconds", r.wall_seconds},
                    {"failed_runs", r.failed_runs},
                    {"band_csv", "band_" + r.name + ".csv"},
                    {"channels", ch}});
  }
  md +=
      "\n## Per channel, all references pooled: the gain over the preset ROM\n\nThe preset ROM is the original "
      "vehicle (every fitted parameter at its original value, every scale 1; the fixed ones as in the "
      "calibration).\n\n| channel | RMSE preset | RMSE MAP | MAP / preset | coverage predictive 90 % | coverage model "
      "band |\n|---|---|---|---|---|---|\n";
  nlohmann::ordered_json pooled;
  for (std::size_t k = 0; k < o.channels.size(); ++k) {
    const Pooled& p = pool[k];
    const double map = std::sqrt(p.sq_map / p.rows), preset = std::sqrt(p.sq_preset / p.rows);
    md += fmt::format("| {} [{}] | {} | {} | {} | {:.1f} % | {:.1f} % |\n", rom::kRomChannelNames[o.channels[k]],
                      rom::kRomChannelUnits[o.channels[k]], num(preset), num(map), num(map / preset, "{:.3f}"),
                      100 * p.in_pred / p.rows, 100 * p.in_model / p.rows);
    pooled[rom::kRomChannelNames[o.channels[k]]] = {{"rmse_preset", jnum(preset)},
                                                    {"rmse_map", jnum(map)},
                                                    {"rmse_median", jnum(std::sqrt(p.sq_median / p.rows))},
                                                    {"coverage_predictive_90", p.in_pred / p.rows},
                                                    {"coverage_model_90", p.in_model / p.rows}};
  }
  md += "\n## Batch runs\n\n| reference | rows | draws | failed runs | wall time [s] |\n|---|---|---|---|---|\n";
  for (const auto& r : o.references)
    md +=
        fmt::format("| {} | {} | {} | {} | {:.3g} |\n", r.name, r.time.size(), o.draws, r.failed_runs, r.wall_seconds);
  md += fmt::format(
      "| total | | {} | {} | {:.3g} |\n\nBands: `band_<reference>.csv` (model band: q05, q95; "
      "predictive band: pred_q05, pred_q95) and `band_<reference>.png`.\n",
      o.draws * long(o.references.size()), o.failed_runs, o.batch_seconds);
  nlohmann::ordered_json j = {{"posterior", posterior},
                              {"model", o.model},
                              {"vehicle", o.vehicle},
                              {"parameters", o.parameters},
                              {"draws", o.draws},
                              {"available_draws", o.available_draws},
                              {"seed", o.seed},
                              {"device", o.device},
                              {"step", o.step},
                              {"noise",
                               "coverage_predictive_90: with each draw's sigma2 noise; "
                               "coverage_model_90 and the band CSV's q05/q95/median: without"},
                              {"failed_runs", o.failed_runs},
                              {"batch_seconds", o.batch_seconds},
                              {"wall_seconds", o.wall_seconds},
                              {"channels", pooled},
                              {"references", refs}};
  write_text_atomically(o.out + "/report.md", md);
  write_text_atomically(o.out + "/summary.json", j.dump(2) + "\n");
}

}  // namespace

RomValidationOutcome run_rom_validation(const RomValidationSettings& s) {
  const auto start = std::chrono::steady_clock::now();
  if (s.draws < 1) throw InputError(fmt::format("--draws {}: expected at least 1", s.draws));
  Posterior p;
  read_params_json(s.posterior + "/rom_params.json", p);
  read_posterior_h5(s.posterior + "/posterior.h5", p);
  rom::RomVehicle base;
  try {
    base = rom::load_rom_vehicle(p.vehicle);
    rom::check_model_effects(base, p.model);
    for (const auto& [n, v] : p.fixed) rom::apply_vary_parameter(base, base, n, v);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}/rom_params.json \"Fit\" (vehicle '{}'): {}", s.posterior, p.vehicle, e.what()));
  }

  // The references, checked before any run.
  std::vector<std::vector<rom::RomReference>> refs;  // one each: RomForward runs one batch per reference
  std::set<std::string> names;
  for (const auto& d : s.references) {
    refs.push_back({rom::read_rom_reference(d)});
    const rom::RomReference& r = refs.back()[0];
    if (!names.insert(r.name).second)
      throw InputError(
          fmt::format("--reference {}: a second reference named '{}'; expected distinct folder names "
                      "(they name band_<reference>.csv)",
                      d, r.name));
    for (rom::RomChannel c : p.channels)
      if (!r.has[c])
        throw InputError(fmt::format("{}/trajectory.csv: no column '{}'; the posterior compares {}", r.dir,
                                     rom::kRomChannelNames[c], fmt::join(channel_names(p.channels), ", ")));
    const double bytes = double(s.draws) * double(r.time.size()) * double(p.channels.size()) * sizeof(double);
    if (bytes > double(kRomValidationMaxBytes))
      throw InputError(fmt::format(
          "--draws {}: {:.3g} GiB of predictions for reference {} ({} rows x {} channels); the limit is {} GiB: "
          "use --draws {} or fewer",
          s.draws, bytes / double(1 << 30), r.dir, r.time.size(), p.channels.size(), kRomValidationMaxBytes >> 30,
          std::max<std::uint64_t>(1, kRomValidationMaxBytes / (r.time.size() * p.channels.size() * sizeof(double)))));
  }

  RomValidationOutcome o;
  o.model = rom::model_name(p.model);
  o.vehicle = p.vehicle;
  o.device = s.device == rom::BatchDevice::kCuda ? "cuda" : "cpu";
  o.out = s.out.empty() ? s.posterior + "/validation" : s.out;
  o.parameters = p.names;
  o.channels = p.channels;
  o.draws = s.draws;
  o.available_draws = static_cast<long>(p.chains * p.draws);
  o.seed = s.seed_given ? s.seed : p.seed;
  o.step = p.step;

  // The draws: (chain, draw) pairs uniformly with replacement, draw k from stream k.
  std::vector<std::vector<double>> params(s.draws, std::vector<double>(p.names.size()));
  std::vector<std::vector<double>> sd(s.draws, std::vector<double>(p.channels.size()));
  for (long k = 0; k < s.draws; ++k) {
    Rng rng = Rng::for_stream(o.seed, static_cast<std::uint64_t>(k));
    const std::size_t at = rng.below(p.chains) * p.draws + rng.below(p.draws);
    for (std::size_t j = 0; j < p.names.size(); ++j) params[k][j] = (*p.values[j])[at];
    for (std::size_t c = 0; c < p.channels.size(); ++c) sd[k][c] = std::sqrt(std::max(0.0, (*p.sigma2[c])[at]));
  }
  spdlog::info("validate-rom: {} draws of {} parameters ({}); channels {}; {} references on the {}", s.draws,
               p.names.size(), fmt::join(p.names, ", "), fmt::join(channel_names(p.channels), ", "), refs.size(),
               o.device);

  fs::create_directories(o.out);
  for (std::size_t ri = 0; ri < refs.size(); ++ri) {
    const rom::RomReference& ref = refs[ri][0];
    const rom::RomForward forward({base, p.model, p.names, p.channels, &refs[ri], p.step, s.device});
    const rom::RomForward preset({base, p.model, {}, p.channels, &refs[ri], p.step, s.device});
    const std::size_t rows = forward.rows_per_channel();
    std::vector<std::vector<double>> f, fmap, fpreset;
    forward(params, f);
    RomReferenceValidation rv{ref.name, ref.dir, ref.time, {}, 0, forward.stats().wall_seconds};
    forward({p.map}, fmap);
    preset({{}}, fpreset);
    for (const auto& d : f) rv.failed_runs += d.empty();
    if (rv.failed_runs == s.draws)
      throw RunError(fmt::format("validate-rom: every one of the {} draws failed on reference {}", s.draws, ref.dir));
    for (std::size_t c = 0; c < p.channels.size(); ++c) {
      RomChannelValidation cv;
      cv.channel = p.channels[c];
      cv.reference = ref.values[cv.channel];
      cv.map = rows_of(fmap[0], c, rows);
      cv.preset = rows_of(fpreset[0], c, rows);
      quantiles(f, c, rows, &cv.q05, &cv.median, &cv.q95);
      rv.channels.push_back(std::move(cv));
    }
    // The predictive band: each draw's prediction plus noise of its sigma2 (stream per draw and reference).
    for (long k = 0; k < s.draws; ++k) {
      if (f[k].empty()) continue;
      Rng rng = Rng::for_stream(o.seed, ((ri + 1) << 32) | static_cast<std::uint64_t>(k));
      for (std::size_t c = 0; c < p.channels.size(); ++c)
        for (std::size_t i = 0; i < rows; ++i) f[k][c * rows + i] += sd[k][c] * rng.normal();
    }
    for (std::size_t c = 0; c < p.channels.size(); ++c) {
      RomChannelValidation& cv = rv.channels[c];
      quantiles(f, c, rows, &cv.pred_q05, nullptr, &cv.pred_q95);
      cv.rmse_map = rmse(cv.reference, cv.map);
      cv.rmse_median = rmse(cv.reference, cv.median);
      cv.rmse_preset = rmse(cv.reference, cv.preset);
      cv.coverage_model = coverage(cv.reference, cv.q05, cv.q95);
      cv.coverage_predictive = coverage(cv.reference, cv.pred_q05, cv.pred_q95);
    }
    f.clear();
    f.shrink_to_fit();
    write_text_atomically(o.out + "/band_" + rv.name + ".csv", csv_band(rv));
    if (s.plots) plot_band(o.out, rv, o.model);
    std::string line;
    for (const auto& cv : rv.channels)
      line += fmt::format("{}{}: RMSE MAP {} (preset {}), coverage {:.0f} % (model band {:.0f} %)",
                          line.empty() ? "" : "; ", rom::kRomChannelNames[cv.channel], num(cv.rmse_map, "{:.3g}"),
                          num(cv.rmse_preset, "{:.3g}"), 100 * cv.coverage_predictive, 100 * cv.coverage_model);
    spdlog::info("validate-rom: {} ({} of {}): {} draws in {:.3g} s, {} failed; {}", rv.name, ri + 1, refs.size(),
                 s.draws, rv.wall_seconds, rv.failed_runs, line);
    o.batch_seconds += rv.wall_seconds;
    o.failed_runs += rv.failed_runs;
    o.references.push_back(std::move(rv));
  }
  o.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  write_outputs(o, s.posterior, p.summary);
  return o;
}

}  // namespace terracal::app
