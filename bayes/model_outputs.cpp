#include "bayes/model_outputs.hpp"

#include <cmath>

#include "core/rng.hpp"

namespace terracal::bayes {
namespace {

std::string squared(const std::string& unit) { return unit.empty() || unit == "1" ? "1" : "(" + unit + ")^2"; }

}  // namespace

std::vector<Eigen::VectorXd> parameter_draws(const CalibrationResult& res) {
  std::vector<Eigen::VectorXd> xs;
  const std::size_t nv = res.names.size();
  for (const auto& chain : res.values)
    for (long d = 0; d < res.draws; ++d) {
      Eigen::VectorXd x(res.num_params);
      for (int v = 0; v < res.num_params; ++v) x[v] = chain[d * nv + v];
      xs.push_back(x);
    }
  return xs;
}

InferenceData make_model_inference_data(const ModelProblem& pb, const CalibrationResult& res, std::uint64_t seed,
                                        int predictive_draws) {
  InferenceData id;
  Group posterior{"posterior", {}};
  for (std::size_t v = 0; v < res.names.size(); ++v) {
    const int p = static_cast<int>(v);
    const std::string unit = p < res.num_params ? pb.parameter(p).unit : squared(pb.channel(p - res.num_params).unit);
    posterior.variables.push_back(chain_draw_variable(res.names[v], unit == "-" ? "1" : unit, res.chains_of(p)));
  }
  id.groups.push_back(posterior);
  id.groups.push_back(sample_stats_group(res.lp, res.accepted));

  // The thinned draws' predictions, one forward batch for all of them.
  const auto keep = thinned_draws(res.draws, predictive_draws);
  const std::size_t nv = res.names.size();
  std::vector<Eigen::VectorXd> xs;
  std::vector<std::pair<int, std::size_t>> which;
  for (int c = 0; c < res.chains; ++c)
    for (std::size_t d : keep) {
      Eigen::VectorXd x(res.num_params);
      for (int v = 0; v < res.num_params; ++v) x[v] = res.values[c][d * nv + v];
      xs.push_back(x);
      which.emplace_back(c, d);
    }
  const auto f = pb.predict(xs);

  Group observed{"observed_data", {}}, constant{"constant_data", {}}, predictive{"posterior_predictive", {}};
  Rng rng = Rng::for_stream(seed, 7);
  std::size_t offset = 0;
  for (int ch = 0; ch < pb.num_channels(); ++ch) {
    const ModelChannel& s = pb.channel(ch);
    const std::string obs_dim = s.name + "_obs";
    observed.variables.push_back({s.name, {obs_dim}, {s.size()}, s.y, s.unit});
    constant.variables.push_back({s.name + "_time", {obs_dim}, {s.size()}, s.x, "s"});
    constant.variables.push_back(
        {s.name + "_reference", {obs_dim}, {s.size()}, std::vector<double>(s.curve.begin(), s.curve.end()), "1"});
    Variable rep{
        s.name, {"chain", "draw", obs_dim}, {static_cast<std::size_t>(res.chains), keep.size(), s.size()}, {}, s.unit};
    for (std::size_t k = 0; k < xs.size(); ++k) {
      const double sd = std::sqrt(res.values[which[k].first][which[k].second * nv + res.num_params + ch]);
      for (std::size_t i = 0; i < s.size(); ++i)  // a failed run (none expected at accepted draws) reads NaN
        rep.data.push_back(f[k].empty() ? std::nan("") : f[k][offset + i] + sd * rng.normal());
    }
    predictive.variables.push_back(rep);
    offset += s.size();
  }
  id.groups.push_back(observed);
  id.groups.push_back(constant);
  id.groups.push_back(predictive);
  return id;
}

nlohmann::ordered_json model_posterior_json(const ModelProblem& pb, const CalibrationResult& res) {
  nlohmann::ordered_json j;
  for (std::size_t v = 0; v < res.names.size(); ++v) {
    const int p = static_cast<int>(v);
    const VariableSummary& s = res.summary[v];
    nlohmann::ordered_json e = {{"mean", s.mean}, {"sd", s.sd},     {"q05", s.q05},          {"q50", s.q50},
                                {"q95", s.q95},   {"rhat", s.rhat}, {"ess_bulk", s.ess_bulk}};
    if (p < res.num_params) {
      e["map"] = res.point.x[p];
      e["unit"] = pb.parameter(p).unit;
    } else {
      e["map"] = res.point.noise_var[p - res.num_params];
      e["unit"] = squared(pb.channel(p - res.num_params).unit);
    }
    j[res.names[v]] = e;
  }
  return j;
}

}  // namespace terracal::bayes
