#include "apps/calibration_run.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "bayes/calibration_outputs.hpp"
#include "bayes/calibrator.hpp"
#include "bayes/posterior_h5.hpp"
#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "core/gnuplot.hpp"
#include "terracal_version.hpp"

namespace terracal::app {
namespace fs = std::filesystem;
using namespace terracal::bayes;

namespace {

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// FNV-1a: a stable 64-bit fingerprint of the inputs and options, so that a checkpoint is resumed
// only by the very same calibration.
std::string fingerprint(const CalibrationRequest& r) {
  const std::string s = fmt::format("{}|{}|{}|{}|{}|{}|{}|{}|{}|{}|{}", TERRACAL_VERSION, file_bytes(r.plate_csv),
                                    r.shear_csv.empty() ? "" : file_bytes(r.shear_csv),
                                    r.priors_json.empty() ? "" : file_bytes(r.priors_json), r.seed, r.chains, r.min_ess,
                                    r.max_draws, r.sampler, r.noise, 1);
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
  return fmt::format("{:016x}", h);
}

void validate(const CalibrationRequest& r) {
  // At least 4 independent chains, so that split R-hat compares 8 half-chains from dispersed starts.
  if (r.chains < 4 || r.chains > 256) throw InputError(fmt::format("--chains {}: expected 4 to 256 chains", r.chains));
  if (r.max_draws < 10) throw InputError(fmt::format("--max-draws {}: expected at least 10 draws per chain", r.max_draws));
  if (!(r.min_ess > 0)) throw InputError(fmt::format("--min-ess {}: expected a positive number", r.min_ess));
  if (r.sampler != "dram" && r.sampler != "ensemble") throw InputError(fmt::format("--sampler '{}': expected dram or ensemble", r.sampler));
  if (r.noise != "relative" && r.noise != "absolute") throw InputError(fmt::format("--noise '{}': expected relative or absolute", r.noise));
  if (r.out_dir.empty()) throw InputError("--out: an output folder is required");
  if (fs::exists(r.out_dir) && !fs::is_directory(r.out_dir))
    throw InputError(fmt::format("--out {}: exists and is not a folder", r.out_dir));
}

}  // namespace

int run_calibration(const CalibrationRequest& req) {
  const auto t0 = std::chrono::steady_clock::now();
  validate(req);
  // Every input is read and checked before the output folder is touched.
  const PlateData plate = load_plate_csv(req.plate_csv);
  std::optional<ShearData> shear;
  if (!req.shear_csv.empty()) shear = load_shear_csv(req.shear_csv);
  const Priors priors = req.priors_json.empty() ? default_priors() : load_priors(req.priors_json);
  const CalibrationProblem problem(plate, shear, priors, req.noise == "relative" ? NoiseModel::kRelative : NoiseModel::kAbsolute);
  for (const auto& note : problem.notes()) spdlog::warn("{}", note);
  if (problem.dim() == 0) throw InputError("every parameter is fixed (by the priors file and the data); nothing to infer");

  fs::create_directories(req.out_dir);
  CalibrationOptions opt;
  opt.seed = req.seed;
  opt.chains = req.chains;
  opt.min_ess = req.min_ess;
  opt.max_draws = req.max_draws;
  opt.sampler = req.sampler == "dram" ? SamplerKind::kDram : SamplerKind::kEnsemble;
  opt.checkpoint_path = req.out_dir + "/.checkpoint.cbor";
  opt.fingerprint = fingerprint(req);
  opt.progress = [](const CalibrationProgress& p) {
    if (p.stage == "warm-up") spdlog::info("warm-up done; sampling until R-hat and ESS targets are met");
    else spdlog::info("{} draws per chain: max R-hat {:.4f}, min bulk ESS {:.0f}", p.draws_per_chain, p.max_rhat, p.min_ess);
  };
  spdlog::info("calibrating: {} plate points{}", problem.set(0).size(),
               shear ? fmt::format(", {} shear points", problem.set(1).size()) : std::string(", no shear data"));
  const CalibrationResult res = calibrate(problem, opt);
  if (res.resumed) spdlog::info("resumed from the checkpoint in {}", req.out_dir);
  for (const auto& note : res.notes) spdlog::warn("{}", note);

  // Files of an earlier run in the same folder go first: the folder never mixes two runs' outputs.
  for (const char* old : {"scm_params.json", "posterior.h5", "summary.txt", "plate_fit.png", "shear_fit.png", "shear_developed.png", "pairs.png"})
    fs::remove(fs::path(req.out_dir) / old);
  const OutputContext ctx{req.sampler, req.seed, opt.warmup};
  write_scm_params_json(req.out_dir + "/scm_params.json", problem, res, ctx);
  const InferenceData idata = make_inference_data(problem, res, req.seed);
  write_inference_data_h5(req.out_dir + "/posterior.h5", idata);
  const std::string report = summary_report(problem, res, ctx);
  write_text_atomically(req.out_dir + "/summary.txt", report);
  if (req.plots) {
    if (gnuplot_available()) write_plots(req.out_dir, problem, res, idata);
    else spdlog::warn("gnuplot not found: no plots written (install gnuplot-nox; scripts/setup.sh does)");
  }
  fs::remove(opt.checkpoint_path);
  std::fputs(report.c_str(), stdout);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  spdlog::info("wrote {}/scm_params.json, posterior.h5, summary.txt{} in {:.2f} s", req.out_dir, req.plots ? ", plots" : "", seconds);
  if (!res.converged) {
    spdlog::error("sampling did not converge ({}); the outputs are written but should not be trusted", res.termination);
    return 1;
  }
  return 0;
}

}  // namespace terracal::app
