#pragma once
// Affine-invariant ensemble sampler of Goodman & Weare (2010), "Ensemble samplers with affine
// invariance", CAMCoS 5(1), with the stretch move, in the two-halves form of emcee
// (Foreman-Mackey et al. 2013): each half moves using walkers of the other half only, which
// keeps the ensemble's joint target invariant and lets a half be evaluated in parallel later.
// Invariance to affine maps means the 1e-2 vs 1e6 parameter scales need no tuning.
#include <vector>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include "bayes/target.hpp"
#include "core/rng.hpp"

namespace terracal::bayes {

struct EnsembleOptions {
  double a = 2.0;  // stretch scale: z ~ g(z) ∝ 1/sqrt(z) on [1/a, a]
};

class EnsembleSampler {
 public:
  // `target` must outlive the sampler. Needs an even number >= 2*dim of walkers (so that each half
  // spans the space), one nuisance vector per walker (or none at all when nuisance_dim == 0), and
  // a finite log density at every walker; std::invalid_argument otherwise.
  EnsembleSampler(const Target& target, const EnsembleOptions& opt, std::vector<Eigen::VectorXd> walkers,
                  std::vector<Eigen::VectorXd> nuisances, Rng rng);

  // One stretch move for every walker (first half, then second half), then the Gibbs update of
  // every walker's own nuisance.
  void step();

  const std::vector<Eigen::VectorXd>& walkers() const { return walkers_; }
  const std::vector<Eigen::VectorXd>& nuisances() const { return nuisances_; }
  const std::vector<double>& log_densities() const { return logp_; }
  const std::vector<ChainStats>& stats() const { return stats_; }  // one per walker
  std::size_t size() const { return walkers_.size(); }

  // Bit-identical continuation, as DramChain::save / load.
  nlohmann::json save() const;
  void load(const nlohmann::json& j);

 private:
  void move_half(std::size_t first, std::size_t other_first);
  void move_half_batched(std::size_t first, std::size_t other_first);
  void stretch_move(std::size_t k, std::size_t other_first);
  void gibbs_update(std::size_t k);

  const Target* target_;
  EnsembleOptions opt_;
  std::vector<Eigen::VectorXd> walkers_, nuisances_;
  std::vector<double> logp_;
  std::vector<ChainStats> stats_;
  Rng rng_;
};

}  // namespace terracal::bayes
