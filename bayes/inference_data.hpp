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

}  // namespace terracal::bayes
