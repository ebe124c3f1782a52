#pragma once
// InferenceData <-> HDF5 file in the layout netCDF-4 uses, so that arviz.from_netcdf and
// xarray.open_datatree load what terracal writes:
//   /                      attributes inference_library = "terracal", inference_library_version
//   /<group>               one HDF5 group per InferenceData group (same attributes)
//   /<group>/<dim>         int64 0..n-1, an HDF5 dimension scale named <dim> (a netCDF
//                          coordinate variable), one per dimension name used in the group
//   /<group>/<variable>    float64, each axis attached to the scale of its dimension;
//                          attribute "units" where Variable::units is non-empty
// Identical input gives a byte-identical file (no timestamps anywhere), and the file appears
// under its final name only once complete (written to a temporary name, then renamed).
#include <string>

#include "bayes/inference_data.hpp"

namespace terracal::bayes {

// Throws RunError naming `path` when the object is inconsistent (dims/shape/data sizes disagree,
// a dimension name has two lengths in one group, duplicate or invalid names, a zero-length
// dimension) or when any HDF5 call fails; no file is left under `path` or a temporary name then.
void write_inference_data_h5(const std::string& path, const InferenceData& idata);

// Reads every group and every non-scale dataset of a file written as above (or by netCDF-4/xarray
// with float data). Each axis's dimension name is taken from the dimension scale attached to it,
// so a file whose variables lack scales is rejected with RunError.
InferenceData read_inference_data_h5(const std::string& path);

}  // namespace terracal::bayes
