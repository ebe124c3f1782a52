#pragma once
// An in-memory ArviZ InferenceData: named groups of named arrays with named dimensions. Written
// to HDF5 as netCDF-4-compatible groups with HDF5 dimension scales (posterior_h5.hpp), so that
// arviz.from_netcdf and xarray.open_datatree load it.
#include <cstddef>
#include <string>
#include <vector>

namespace terracal::bayes {

struct Variable {
  std::string name;
  std::vector<std::string> dims;   // e.g. {"chain", "draw"} or {"chain", "draw", "plate_obs"}
  std::vector<std::size_t> shape;  // same length as dims
  std::vector<double> data;        // row-major, product(shape) values
  std::string units;               // optional, written as the attribute "units"
};

struct Group {
  std::string name;  // "posterior", "sample_stats", "observed_data", "posterior_predictive"
  std::vector<Variable> variables;
};

struct InferenceData {
  std::vector<Group> groups;
};

// Indices of `keep` draws spread evenly over `draws` (all of them when there are fewer).
std::vector<std::size_t> thinned_draws(long draws, int keep);
// A (chain, draw) variable from per-chain draws of equal length.
Variable chain_draw_variable(const std::string& name, const std::string& units,
                             const std::vector<std::vector<double>>& per_chain);
// sample_stats: lp, and each chain's running acceptance rate up to each draw (accepted: 0/1 per draw).
Group sample_stats_group(const std::vector<std::vector<double>>& lp, const std::vector<std::vector<double>>& accepted);

}  // namespace terracal::bayes
