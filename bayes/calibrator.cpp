#include "bayes/calibrator.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>

#include <omp.h>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "bayes/box_transform.hpp"
#include "bayes/dram.hpp"
#include "bayes/ensemble.hpp"
#include "bayes/independence.hpp"
#include "bayes/proposal_adaptation.hpp"
#include "bayes/safe_eval.hpp"
#include "core/checkpoint_file.hpp"
#include "core/errors.hpp"

namespace terracal::bayes {
namespace {

constexpr double kMaxStartLogit = 3.0;  // the independence proposal's start, in box coordinates

// Draws recorded per chain: values row-major (draw, variable), log density, moved or not.
struct ChainRecord {
  std::vector<double> values, lp, accepted;
};

// The two samplers behind one face: advance every chain by n iterations, recording if asked.
class MultiChain {
 public:
  virtual ~MultiChain() = default;
  virtual int chains() const = 0;
  virtual void advance(int iterations, bool adapt, std::vector<ChainRecord>* record) = 0;
  virtual long failed_evaluations() const = 0;
  virtual nlohmann::json save() const = 0;
  virtual void load(const nlohmann::json& j) = 0;
};

void record_state(ChainRecord& r, const Eigen::VectorXd& x, const Eigen::VectorXd& nuisance, double lp, bool moved) {
  r.values.insert(r.values.end(), x.data(), x.data() + x.size());
  r.values.insert(r.values.end(), nuisance.data(), nuisance.data() + nuisance.size());
  r.lp.push_back(lp);
  r.accepted.push_back(moved ? 1.0 : 0.0);
}

class DramChains : public MultiChain {
 public:
  // `box`: the chains run in its unbounded coordinates (target, starts and covariance given in them)
  // and record the target's own; null: no transform.
  DramChains(const Target& target, const std::vector<Eigen::VectorXd>& starts, const Eigen::VectorXd& noise0,
             const Eigen::MatrixXd& covariance, std::uint64_t seed, const BoxTransform* box = nullptr)
      : box_(box) {
    for (std::size_t c = 0; c < starts.size(); ++c)
      chains_.emplace_back(target, DramOptions{}, starts[c], noise0, covariance, Rng::for_stream(seed, 100 + c));
  }
  int chains() const override { return static_cast<int>(chains_.size()); }
  void advance(int iterations, bool adapt, std::vector<ChainRecord>* record) override {
    // Chains are independent: one per thread; each owns its RNG, so the result is thread-count free.
    // A team of one thread per chain, so that the threads left over go to each chain's own work (the
    // steady wheel's slips, CalibrationProblem::predict_wheel).
    const int team = std::max(1, std::min(chains(), omp_get_max_threads()));
#pragma omp parallel for schedule(static, 1) num_threads(team)
    for (int c = 0; c < chains(); ++c) {
      DramChain& ch = chains_[c];
      for (int i = 0; i < iterations; ++i) {
        const long before = ch.stats().accepted;
        ch.step(adapt);
        if (record)
          record_state((*record)[c], box_ ? box_->to_x(ch.x()) : ch.x(), ch.nuisance(), ch.log_density(),
                       ch.stats().accepted > before);
      }
    }
  }
  long failed_evaluations() const override {
    long n = 0;
    for (const auto& ch : chains_) n += ch.stats().failed_evaluations;
    return n;
  }
  nlohmann::json save() const override {
    nlohmann::json j = nlohmann::json::array();
    for (const auto& ch : chains_) j.push_back(ch.save());
    return j;
  }
  void load(const nlohmann::json& j) override {
    for (std::size_t c = 0; c < chains_.size(); ++c) chains_[c].load(j.at(c));
  }

 private:
  std::vector<DramChain> chains_;
  const BoxTransform* box_ = nullptr;
};

class Ensemble : public MultiChain {
 public:
  Ensemble(const Target& target, const std::vector<Eigen::VectorXd>& starts, const Eigen::VectorXd& noise0,
           std::uint64_t seed)
      : sampler_(target, EnsembleOptions{}, starts, std::vector<Eigen::VectorXd>(starts.size(), noise0),
                 Rng::for_stream(seed, 99)) {}
  int chains() const override { return static_cast<int>(sampler_.size()); }
  void advance(int iterations, bool, std::vector<ChainRecord>* record) override {
    for (int i = 0; i < iterations; ++i) {
      std::vector<long> before(sampler_.size());
      for (std::size_t k = 0; k < sampler_.size(); ++k) before[k] = sampler_.stats()[k].accepted;
      sampler_.step();
      if (record)
        for (std::size_t k = 0; k < sampler_.size(); ++k)
          record_state((*record)[k], sampler_.walkers()[k], sampler_.nuisances()[k], sampler_.log_densities()[k],
                       sampler_.stats()[k].accepted > before[k]);
    }
  }
  long failed_evaluations() const override {
    long n = 0;
    for (const auto& s : sampler_.stats()) n += s.failed_evaluations;
    return n;
  }
  nlohmann::json save() const override { return sampler_.save(); }
  void load(const nlohmann::json& j) override { sampler_.load(j); }

 private:
  EnsembleSampler sampler_;
};

// Independence chains: the Laplace proposal, refitted to the chains' pooled states after each
// quarter of the warm-up (from that quarter's states) unless importance sampling already fitted it
// to the posterior; fixed while draws are kept. A quarter of a short warm-up holds few, strongly
// correlated states: refitting an adapted proposal to them made it worse (on the full-vehicle
// references with 8 chains, bulk ESS 31 against 661 after 1,151 draws; docs/decisions.md).
class Independence : public MultiChain {
 public:
  // With a box, the target, starts and proposal are in its unbounded coordinates; draws are
  // recorded in the original ones (and their log density without the Jacobian).
  Independence(const Target& target, const std::vector<Eigen::VectorXd>& starts, const Eigen::VectorXd& noise0,
               const Eigen::VectorXd& mean, const Eigen::MatrixXd& covariance, std::uint64_t seed,
               const BoxTransform* box, const IndependenceOptions& options, bool refit_in_warmup)
      : sampler_(target, options, mean, covariance, starts,
                 std::vector<Eigen::VectorXd>(starts.size(), noise0), Rng::for_stream(seed, 98)),
        box_(box),
        refit_in_warmup_(refit_in_warmup) {}
  int chains() const override { return static_cast<int>(sampler_.size()); }
  void advance(int iterations, bool adapt, std::vector<ChainRecord>* record) override {
    std::vector<Eigen::VectorXd> pool;
    for (int i = 0; i < iterations; ++i) {
      std::vector<long> before(sampler_.size());
      for (std::size_t k = 0; k < sampler_.size(); ++k) before[k] = sampler_.stats()[k].accepted;
      sampler_.step();
      if (adapt && refit_in_warmup_) {
        pool.insert(pool.end(), sampler_.states().begin(), sampler_.states().end());
        const int every = std::max(1, iterations / 4);
        if ((i + 1) % every == 0 || i + 1 == iterations) {
          sampler_.refit(pool);
          pool.clear();
        }
      }
      if (record)
        for (std::size_t k = 0; k < sampler_.size(); ++k) {
          const Eigen::VectorXd& u = sampler_.states()[k];
          const double lp = sampler_.log_density(k) - (box_ ? box_->log_jacobian(u) : 0.0);
          record_state((*record)[k], box_ ? box_->to_x(u) : u, sampler_.nuisances()[k], lp,
                       sampler_.stats()[k].accepted > before[k]);
        }
    }
  }
  long failed_evaluations() const override {
    long n = 0;
    for (const auto& s : sampler_.stats()) n += s.failed_evaluations;
    return n;
  }
  nlohmann::json save() const override { return sampler_.save(); }
  void load(const nlohmann::json& j) override { sampler_.load(j); }

 private:
  IndependenceSampler sampler_;
  const BoxTransform* box_;
  bool refit_in_warmup_;
};

// Starting points dispersed around the MAP: MAP + 2 L z (L the Cholesky factor of the Laplace
// covariance), redrawn until inside the support, so that R-hat can detect chains that disagree.
// A start that cannot be dispersed is reported: identical chains would make R-hat meaningless.
// The log density at a candidate start, -inf where the forward model fails.
double start_log_density(const Target& target, const Eigen::VectorXd& x, const Eigen::VectorXd& noise_var) {
  ChainStats ignored;
  return safe_log_density(target, x, noise_var, ignored);
}

std::vector<Eigen::VectorXd> dispersed_starts(const Target& target, const PointEstimate& est, int count,
                                              std::uint64_t seed, std::vector<std::string>& notes) {
  Rng rng = Rng::for_stream(seed, 1);
  const Eigen::MatrixXd L = est.covariance.llt().matrixL();  // positive definite by construction (point_estimate)
  std::vector<Eigen::VectorXd> starts;
  int undispersed = 0;
  for (int c = 0; c < count; ++c) {
    Eigen::VectorXd x = est.x;
    bool found = false;
    for (int attempt = 0; attempt < 200 && !found; ++attempt) {
      Eigen::VectorXd z(target.dim);
      for (int j = 0; j < target.dim; ++j) z[j] = rng.normal();
      const Eigen::VectorXd y = est.x + 2.0 * L * z;
      if (std::isfinite(start_log_density(target, y, est.noise_var))) {
        x = y;
        found = true;
      }
    }
    undispersed += !found;
    starts.push_back(x);
  }
  if (undispersed > 0)
    notes.push_back(
        fmt::format("{} of {} chains could not be started away from the MAP point (every dispersed start fell outside "
                    "the prior support); they start at the MAP",
                    undispersed, count));
  return starts;
}

// A parameter whose draws never change within some chain has not been explored: R-hat and ESS of
// constant chains are 1 and N by convention, which must not pass for convergence.
bool some_chain_is_stuck(const Chains& chains) {
  for (const auto& c : chains)
    if (std::all_of(c.begin(), c.end(), [&](double v) { return v == c.front(); })) return true;
  return false;
}

// ---- checkpoint -------------------------------------------------------------------------------

struct Checkpoint {
  bool warmup_done = false;
  std::vector<ChainRecord> records;
  nlohmann::json sampler;
};

// Version 2: sealed by core/checkpoint_file (version 1 was bare CBOR).
const CheckpointKind kMcmcCheckpoint{"terracal-mcmc-checkpoint", 2};

void write_checkpoint(const std::string& path, const std::string& fingerprint, const Checkpoint& cp) {
  nlohmann::json j;
  j["warmup_done"] = cp.warmup_done;
  j["sampler"] = cp.sampler;
  j["records"] = nlohmann::json::array();
  for (const auto& r : cp.records)
    j["records"].push_back({{"values", r.values}, {"lp", r.lp}, {"accepted", r.accepted}});
  const std::vector<std::uint8_t> bytes = nlohmann::json::to_cbor(j);
  write_checkpoint_file(path, kMcmcCheckpoint, fingerprint,
                        std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

// The records of a checkpoint's payload; throws when they do not fit `chains` chains of `nv` variables.
std::vector<ChainRecord> decode_records(const nlohmann::json& j, std::size_t chains, std::size_t nv) {
  std::vector<ChainRecord> records;
  for (const auto& r : j.at("records"))
    records.push_back({r.at("values").get<std::vector<double>>(), r.at("lp").get<std::vector<double>>(),
                       r.at("accepted").get<std::vector<double>>()});
  if (records.size() != chains) throw std::runtime_error(fmt::format("{} chains, expected {}", records.size(), chains));
  for (const auto& r : records)
    if (r.lp.size() != records[0].lp.size() || r.accepted.size() != r.lp.size() || r.values.size() != nv * r.lp.size())
      throw std::runtime_error("chains of different lengths");
  return records;
}

// Restores `cp` and the sampler from the checkpoint at `path`. Returns what to tell the user: empty
// when there is no checkpoint; otherwise `resumed` says whether the run continues from it.
std::string restore_checkpoint(const std::string& path, const std::string& fingerprint, std::size_t nv, Checkpoint& cp,
                               MultiChain& sampler, bool& resumed) {
  resumed = false;
  const CheckpointRead read = read_checkpoint_file(path, kMcmcCheckpoint, fingerprint);
  if (read.state == CheckpointState::kMissing) return {};
  std::string why = read.why;
  if (read.state == CheckpointState::kValid) {
    try {
      const nlohmann::json j = nlohmann::json::from_cbor(read.payload);
      Checkpoint loaded;
      loaded.warmup_done = j.at("warmup_done").get<bool>();
      loaded.sampler = j.at("sampler");
      loaded.records = decode_records(j, cp.records.size(), nv);
      sampler.load(loaded.sampler);
      cp = std::move(loaded);
      resumed = true;
      return fmt::format("resuming from {}: {}, {} draws per chain", path,
                         cp.warmup_done ? "warm-up done" : "in warm-up", cp.records[0].lp.size());
    } catch (const std::exception& e) {  // sealed intact, yet not this sampler's state
      why = std::string("its content does not fit this calibration: ") + e.what();
    }
  }
  return fmt::format("checkpoint {} ignored, the calibration starts over: {}", path, why);
}

}  // namespace

Chains CalibrationResult::chains_of(int v) const {
  const std::size_t nv = names.size();
  Chains out(values.size());
  for (std::size_t c = 0; c < values.size(); ++c) {
    out[c].resize(draws);
    for (long d = 0; d < draws; ++d) out[c][d] = values[c][d * nv + v];
  }
  return out;
}

// The convergence test after each block: R-hat and bulk ESS of every free parameter against the
// targets, or the draw cap. Fills res.values and, when done, res.termination.
bool sampling_done(const CalibrationOptions& opt, const Checkpoint& cp, CalibrationResult& res) {
  res.values.clear();
  for (const auto& r : cp.records) res.values.push_back(r.values);
  double max_rhat = 0, min_ess = 1e300;
  bool stuck = false;
  for (int v = 0; v < res.num_params; ++v) {
    const Chains ch = res.chains_of(v);
    max_rhat = std::max(max_rhat, rhat_rank(ch));
    min_ess = std::min(min_ess, ess_bulk(ch));
    stuck = stuck || some_chain_is_stuck(ch);
  }
  if (stuck) max_rhat = std::numeric_limits<double>::infinity();
  if (opt.progress) opt.progress({"sampling", res.draws, max_rhat, min_ess, {}});
  if (max_rhat < opt.max_rhat && min_ess >= opt.min_ess) {
    res.converged = true;
    res.termination = fmt::format("converged: max R-hat {:.4f} < {}, min bulk ESS {:.0f} >= {}", max_rhat, opt.max_rhat,
                                  min_ess, opt.min_ess);
    return true;
  }
  if (res.draws >= opt.max_draws) {
    res.termination = fmt::format(
        "NOT converged: draw cap {} per chain reached with max R-hat {:.4f} (target < {}) "
        "and min bulk ESS {:.0f} (target >= {})",
        opt.max_draws, max_rhat, opt.max_rhat, min_ess, opt.min_ess);
    return true;
  }
  return false;
}

// Log densities, acceptances and the summaries of the finished chains into res.
void collect_draws(const Checkpoint& cp, long failed_evaluations, int count, int nv, CalibrationResult& res) {
  res.lp.clear();
  res.accepted.clear();
  double acc = 0;
  for (const auto& r : cp.records) {
    res.lp.push_back(r.lp);
    res.accepted.push_back(r.accepted);
    for (double a : r.accepted) acc += a;
  }
  res.acceptance_rate = acc / double(count * res.draws);
  res.failed_evaluations = failed_evaluations;
  for (int v = 0; v < nv; ++v) res.summary.push_back(summarize(res.chains_of(v)));
}

CalibrationResult calibrate(const CalibrationProblem& pb, const CalibrationOptions& opt) {
  if (pb.dim() == 0) throw InputError("calibrate: every parameter is fixed; nothing to infer");
  if (opt.chains < 2) throw InputError(fmt::format("chains {}: at least 2 chains are needed for R-hat", opt.chains));
  CalibrationResult res;
  res.point = estimate_point(pb, PointEstimateOptions{.seed = opt.seed, .global_evaluations = opt.global_evaluations});
  for (int i : pb.free_indices()) res.names.emplace_back(kShortNames[i]);
  res.num_params = pb.dim();
  for (int t = 0; t < pb.num_types(); ++t) res.names.push_back("sigma2_" + pb.set(t).name);
  // With the annulus's law scaled the set's k is pinned by a few wheel rows only: its posterior has a
  // long tail towards large k, which DRAM crosses far faster in the box's logit coordinates.
  CalibrationOptions o = opt;
  o.dram_in_box = opt.dram_in_box || pb.annulus_scaled();
  sample_posterior(pb.target(), o, res);
  return res;
}

void sample_posterior(const Target& target, const CalibrationOptions& opt, CalibrationResult& res) {
  if (opt.chains < 2) throw InputError(fmt::format("chains {}: at least 2 chains are needed for R-hat", opt.chains));
  if (opt.tries < 1) throw InputError(fmt::format("tries {}: expected at least 1 point per chain and step", opt.tries));
  if (opt.lookahead < 1)
    throw InputError(fmt::format("lookahead {}: expected at least 1 step per batch of proposals", opt.lookahead));
  if (opt.delayed_acceptance && (opt.sampler != SamplerKind::kIndependence || !opt.local_moves))
    throw InputError("delayed acceptance screens the independence sampler's random-walk move: it needs that sampler "
                     "with local moves");
  const int dim = target.dim;
  int count = opt.chains;
  if (opt.sampler == SamplerKind::kEnsemble)
    count = std::max(opt.chains, 2 * dim + 2) + std::max(opt.chains, 2 * dim + 2) % 2;
  if (res.point.unconstrained_directions > 0)
    res.notes.push_back(
        fmt::format("the data do not constrain {} combination(s) of the free parameters (the least-squares "
                    "covariance is singular): the posterior there is set by the priors and sampling may not "
                    "converge; fix a parameter or give an informative prior",
                    res.point.unconstrained_directions));
  // Independence chains (and DRAM chains with dram_in_box) run in the box's unbounded coordinates
  // where the target has one. Independence chains start from, and propose with, the proposal adapted
  // to the posterior by importance sampling (the Laplace approximation where adaptation is off or
  // fails); DRAM chains start around the least-squares point with its covariance, both carried over.
  std::unique_ptr<BoxTransform> box;
  Target unbounded;
  const Target* sampled = &target;
  PointEstimate proposal = res.point;
  bool refit_in_warmup = true;
  const bool boxed = opt.sampler == SamplerKind::kIndependence || (opt.sampler == SamplerKind::kDram && opt.dram_in_box);
  if (boxed && target.lower.size() == dim && target.upper.size() == dim) {
    box = std::make_unique<BoxTransform>(target.lower, target.upper);
    unbounded = in_unbounded_coordinates(target, *box);
    sampled = &unbounded;
    proposal.x = box->to_u(res.point.x);
    proposal.covariance = box->covariance_to_u(proposal.x, res.point.covariance);
    // A least-squares point on a bound lies 10-20 logit units out, many proposal widths from the
    // posterior's mass where the data hardly pin that parameter (a roll damping at its lower bound
    // left importance sampling at tempering exponent 0.24 after 12 rounds, and the chains stuck):
    // the proposal starts at most 3 units out (within 5 % of the box's edge) and adapts from there,
    // at least one unit wide there (the Laplace width at the bound says nothing about the box's middle).
    // A coordinate that the Laplace approximation leaves wider than its whole box (a logistic over the
    // box has variance pi^2 / 3) starts at that width instead.
    for (int j = 0; j < dim && opt.sampler == SamplerKind::kIndependence; ++j) {
      const bool clamped = std::abs(proposal.x[j]) > kMaxStartLogit;
      proposal.x[j] = std::clamp(proposal.x[j], -kMaxStartLogit, kMaxStartLogit);
      const double v = proposal.covariance(j, j);
      const double target = v > 4.0 ? 4.0 : clamped && v < 1.0 ? 1.0 : v;
      if (target != v && v > 0) {
        const double f = std::sqrt(target / v);
        proposal.covariance.row(j) *= f;
        proposal.covariance.col(j) *= f;
      }
    }
  }
  if (opt.sampler == SamplerKind::kIndependence && opt.adaptation_rounds > 0) {
    Rng rng = Rng::for_stream(opt.seed, 97);
    ProposalAdaptationOptions ao;
    ao.max_rounds = opt.adaptation_rounds;
    ao.points = std::max(opt.adaptation_points, 2 * dim + 2);
    ao.final_ess = opt.adaptation_final_ess;
    const AdaptedProposal a =
        adapt_proposal(*sampled, proposal.x, proposal.covariance, res.point.noise_var, ao, rng);
    proposal.x = a.mean;
    proposal.covariance = a.covariance;
    refit_in_warmup = !a.reached_posterior;
    if (!a.reached_posterior)
      res.notes.push_back(
          fmt::format("the independence proposal did not reach the posterior in {} rounds of importance sampling "
                      "(last tempering exponent {:.3g}): chains may move rarely and converge slowly",
                      a.rounds, a.beta));
    if (opt.progress)
      opt.progress({"adapted", 0, 0, 0,
                    fmt::format("{} rounds, {} runs, tempering exponent {:.3g}, ESS {:.0f} of {}", a.rounds,
                                a.evaluations, a.beta, a.ess, ao.points)});
  }
  const auto starts = dispersed_starts(*sampled, proposal, count, opt.seed, res.notes);
  auto make_sampler = [&]() -> std::unique_ptr<MultiChain> {
    if (opt.sampler == SamplerKind::kDram)
      return box ? std::make_unique<DramChains>(*sampled, starts, res.point.noise_var, proposal.covariance, opt.seed,
                                                box.get())
                 : std::make_unique<DramChains>(target, starts, res.point.noise_var, res.point.covariance, opt.seed);
    if (opt.sampler == SamplerKind::kIndependence)
      return std::make_unique<Independence>(*sampled, starts, res.point.noise_var, proposal.x, proposal.covariance,
                                            opt.seed, box.get(),
                                            IndependenceOptions{.scale = opt.proposal_scale,
                                                                .local_moves = opt.local_moves,
                                                                .tries = opt.tries,
                                                                .lookahead = opt.lookahead,
                                                                .delayed_acceptance = opt.delayed_acceptance},
                                            refit_in_warmup);
    return std::make_unique<Ensemble>(target, starts, res.point.noise_var, opt.seed);
  };
  std::unique_ptr<MultiChain> sampler = make_sampler();

  Checkpoint cp;
  cp.records.resize(count);
  if (!opt.checkpoint_path.empty()) {
    const std::string said =
        restore_checkpoint(opt.checkpoint_path, opt.fingerprint, res.names.size(), cp, *sampler, res.resumed);
    if (!res.resumed && !said.empty()) sampler = make_sampler();  // a failed load may have left a partial state
    if (!said.empty() && opt.progress)
      opt.progress(
          {res.resumed ? "resumed" : "restarted", res.resumed ? long(cp.records[0].lp.size()) : 0, 0, 0, said});
  }
  auto save = [&] {
    if (opt.checkpoint_path.empty()) return;
    cp.sampler = sampler->save();
    write_checkpoint(opt.checkpoint_path, opt.fingerprint, cp);
  };
  if (!cp.warmup_done) {
    sampler->advance(opt.warmup, true, nullptr);
    cp.warmup_done = true;
    save();
    if (opt.progress) opt.progress({"warm-up", 0, 0, 0, {}});
  }

  res.chains = count;
  const int nv = static_cast<int>(res.names.size());
  for (;;) {
    res.draws = static_cast<long>(cp.records[0].lp.size());
    if (res.draws >= 4 && sampling_done(opt, cp, res)) break;
    // Blocks grow with the chain (a quarter of the draws so far), so convergence checks and
    // checkpoint writes cost O(N log N) overall instead of O(N^2).
    const long block = opt.growing_blocks ? std::max<long>(opt.block, res.draws / 4) : opt.block;
    const int n = static_cast<int>(std::min<long>(block, std::max<long>(opt.max_draws - res.draws, 1)));
    sampler->advance(n, false, &cp.records);
    save();
  }

  collect_draws(cp, sampler->failed_evaluations(), count, nv, res);
}

}  // namespace terracal::bayes
