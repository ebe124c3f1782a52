#include "bayes/inference_data.hpp"

#include <algorithm>

namespace terracal::bayes {

std::vector<std::size_t> thinned_draws(long draws, int keep) {
  std::vector<std::size_t> idx;
  const long n = std::min<long>(draws, keep);
  for (long k = 0; k < n; ++k) idx.push_back(static_cast<std::size_t>((k * draws) / n));
  return idx;
}

Variable chain_draw_variable(const std::string& name, const std::string& units,
                             const std::vector<std::vector<double>>& per_chain) {
  Variable v{name, {"chain", "draw"}, {per_chain.size(), per_chain.empty() ? 0 : per_chain[0].size()}, {}, units};
  for (const auto& c : per_chain) v.data.insert(v.data.end(), c.begin(), c.end());
  return v;
}

Group sample_stats_group(const std::vector<std::vector<double>>& lp, const std::vector<std::vector<double>>& accepted) {
  std::vector<std::vector<double>> rate(accepted.size());
  for (std::size_t c = 0; c < accepted.size(); ++c) {
    double s = 0;
    for (std::size_t d = 0; d < accepted[c].size(); ++d) rate[c].push_back((s += accepted[c][d]) / double(d + 1));
  }
  return {"sample_stats", {chain_draw_variable("lp", "1", lp), chain_draw_variable("acceptance_rate", "1", rate)}};
}

}  // namespace terracal::bayes
