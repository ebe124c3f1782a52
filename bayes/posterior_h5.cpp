#include "bayes/posterior_h5.hpp"

#include <hdf5.h>
#include <hdf5_hl.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <numeric>
#include <utility>
#include <vector>

#include "core/hdf5_util.hpp"
#include "core/quiet_hdf5_errors.hpp"
#include "terracal_version.hpp"

namespace terracal::bayes {
namespace {

constexpr const char* kFileKind = "InferenceData file";

// ---------------------------------------------------------------------------------------------
// Validation: everything that can be wrong with the in-memory object is found before the file
// is created, so a bad object never produces a half-written temporary.

using DimList = std::vector<std::pair<std::string, std::size_t>>;  // in order of first use

DimList group_dimensions(const Group& g, const H5File& f) {
  const std::string where = "group '" + g.name + "'";
  check_object_name(g.name, f, "group");
  DimList dims;
  std::map<std::string, std::size_t> length;
  std::map<std::string, std::string> first_user;  // which variable fixed a dimension's length
  for (const Variable& v : g.variables) {
    check_object_name(v.name, f, "variable");
    const std::string var_where = where + ", variable '" + v.name + "'";
    if (v.dims.size() != v.shape.size())
      refuse(f, var_where + ": " + std::to_string(v.dims.size()) + " dimension names but shape has " +
                    std::to_string(v.shape.size()) + " entries");
    std::size_t count = 1;
    for (std::size_t a = 0; a < v.dims.size(); ++a) {
      const std::string& d = v.dims[a];
      check_object_name(d, f, "dimension");
      if (v.shape[a] == 0) refuse(f, var_where + ": dimension '" + d + "' has length 0");
      for (std::size_t b = 0; b < a; ++b)
        if (v.dims[b] == d)  // xarray cannot index a repeated dimension; use e.g. p_dim_0, p_dim_1
          refuse(f, var_where + ": dimension '" + d + "' is used twice");
      auto [it, inserted] = length.emplace(d, v.shape[a]);
      if (inserted) {
        dims.emplace_back(d, v.shape[a]);
        first_user[d] = v.name;
      } else if (it->second != v.shape[a]) {
        refuse(f, var_where + ": dimension '" + d + "' has length " + std::to_string(v.shape[a]) + " but length " +
                      std::to_string(it->second) + " in variable '" + first_user[d] + "'");
      }
      count *= v.shape[a];
    }
    if (v.data.size() != count)
      refuse(f, var_where + ": shape holds " + std::to_string(count) + " values but data has " +
                    std::to_string(v.data.size()));
  }
  // Dimension scales and variables share the group's namespace.
  for (std::size_t i = 0; i < g.variables.size(); ++i) {
    const std::string& n = g.variables[i].name;
    if (length.count(n)) refuse(f, where + ": variable '" + n + "' has the name of a dimension");
    for (std::size_t j = 0; j < i; ++j)
      if (g.variables[j].name == n) refuse(f, where + ": variable '" + n + "' appears twice");
  }
  return dims;
}

// ---------------------------------------------------------------------------------------------
// Writing

void write_library_attributes(hid_t loc, const H5File& f) {
  write_text_attribute(loc, "inference_library", "terracal", f);
  write_text_attribute(loc, "inference_library_version", TERRACAL_VERSION, f);
}

void write_group(hid_t file, const Group& g, const DimList& dims, hid_t gcpl, hid_t dcpl, const H5File& f) {
  const std::string gw = "group '" + g.name + "'";
  H5Handle grp = create_group(file, g.name, gcpl, f);
  write_library_attributes(grp.get(), f);

  // Dimension scales first (netCDF-4 defines dimensions before the variables using them):
  // ArviZ-style integer coordinates 0..n-1, named by H5DSset_scale so readers see a coordinate
  // variable (a NAME of "This is a netCDF dimension but not a netCDF variable" would hide it).
  std::map<std::string, H5Handle> scales;
  for (const auto& [dim, n] : dims) {
    const std::string what = gw + " dimension '" + dim + "'";
    H5Handle ds = create_dataset(grp.get(), dim, H5T_STD_I64LE, {static_cast<hsize_t>(n)}, dcpl, f, what);
    std::vector<std::int64_t> index(n);
    std::iota(index.begin(), index.end(), std::int64_t{0});
    check_rc(H5Dwrite(ds.get(), H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, index.data()), f, "writing " + what);
    check_rc(H5DSset_scale(ds.get(), dim.c_str()), f, "making " + what + " a dimension scale");
    scales.emplace(dim, std::move(ds));
  }

  for (const Variable& v : g.variables) {
    const std::string what = gw + " variable '" + v.name + "'";
    const std::vector<hsize_t> extent(v.shape.begin(), v.shape.end());
    H5Handle ds = create_dataset(grp.get(), v.name, H5T_IEEE_F64LE, extent, dcpl, f, what);
    check_rc(H5Dwrite(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data.data()), f, "writing " + what);
    for (std::size_t a = 0; a < v.dims.size(); ++a)
      check_rc(H5DSattach_scale(ds.get(), scales.at(v.dims[a]).get(), static_cast<unsigned>(a)), f,
               "attaching dimension '" + v.dims[a] + "' to axis " + std::to_string(a) + " of " + what);
    if (!v.units.empty()) write_text_attribute(ds.get(), "units", v.units, f);
    ds.close(f, what);
  }
  for (auto& [dim, ds] : scales) ds.close(f, gw + " dimension '" + dim + "'");
  grp.close(f, gw);
}

void write_file(const std::string& tmp, const H5File& f, const InferenceData& idata, const std::vector<DimList>& dims) {
  // Root group: its creation properties live in the file creation property list.
  H5Handle fcpl = timeless_plist(H5P_FILE_CREATE, f);
  H5Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, f, "creating a file access property list");
  // The oldest object formats that can hold these features (as netCDF-4 does), so that readers
  // built on HDF5 1.8 open the file too.
  check_rc(H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_EARLIEST, H5F_LIBVER_V18), f, "setting format bounds");
  H5Handle gcpl = timeless_plist(H5P_GROUP_CREATE, f);
  H5Handle dcpl = timeless_plist(H5P_DATASET_CREATE, f);

  H5Handle file(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, fcpl.get(), fapl.get()), H5Fclose, f,
                "cannot create temporary file '" + tmp + "'");
  write_library_attributes(file.get(), f);
  for (std::size_t i = 0; i < idata.groups.size(); ++i)
    write_group(file.get(), idata.groups[i], dims[i], gcpl.get(), dcpl.get(), f);
  check_rc(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), f, "flushing '" + tmp + "'");
  file.close(f, "'" + tmp + "'");
  dcpl.close(f, "a property list");
  gcpl.close(f, "a property list");
  fapl.close(f, "a property list");
  fcpl.close(f, "a property list");
}

// ---------------------------------------------------------------------------------------------
// Reading

// Link names of a group in creation order where tracked (files written here, by netCDF), else
// by name (files written by tools that do not track order, e.g. plain h5py).
std::vector<std::string> link_names(hid_t group, const H5File& f, const std::string& where) {
  H5Handle gcpl(H5Gget_create_plist(group), H5Pclose, f, "reading the creation properties of " + where);
  unsigned flags = 0;
  check_rc(H5Pget_link_creation_order(gcpl.get(), &flags), f, "reading the link order of " + where);
  gcpl.close(f, "a property list");
  const H5_index_t index = (flags & H5P_CRT_ORDER_TRACKED) ? H5_INDEX_CRT_ORDER : H5_INDEX_NAME;

  H5G_info_t info;
  check_rc(H5Gget_info(group, &info), f, "listing " + where);
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t n = H5Lget_name_by_idx(group, ".", index, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (n < 0) fail(f, "reading a link name in " + where);
    std::string name(static_cast<std::size_t>(n) + 1, '\0');
    if (H5Lget_name_by_idx(group, ".", index, H5_ITER_INC, i, name.data(), name.size(), H5P_DEFAULT) < 0)
      fail(f, "reading a link name in " + where);
    name.resize(static_cast<std::size_t>(n));
    names.push_back(std::move(name));
  }
  return names;
}

// Scalar string attribute, fixed-length (netCDF NC_CHAR, what we write) or variable-length
// (netCDF NC_STRING, what h5py writes).
std::string read_text_attribute(hid_t loc, const std::string& name, const H5File& f, const std::string& where) {
  const std::string what = "attribute '" + name + "' of " + where;
  H5Handle attr(H5Aopen(loc, name.c_str(), H5P_DEFAULT), H5Aclose, f, "opening " + what);
  H5Handle type(H5Aget_type(attr.get()), H5Tclose, f, "reading the type of " + what);
  if (H5Tget_class(type.get()) != H5T_STRING) refuse(f, what + " is not text");
  H5Handle space(H5Aget_space(attr.get()), H5Sclose, f, "reading the dataspace of " + what);
  if (H5Sget_simple_extent_npoints(space.get()) != 1) refuse(f, what + " is not a single string");
  const htri_t variable = H5Tis_variable_str(type.get());
  if (variable < 0) fail(f, "reading the type of " + what);
  std::string value;
  if (variable) {
    H5Handle mem(H5Tcopy(H5T_C_S1), H5Tclose, f, "creating a string type");
    check_rc(H5Tset_size(mem.get(), H5T_VARIABLE), f, "creating a string type");
    check_rc(H5Tset_cset(mem.get(), H5Tget_cset(type.get())), f, "creating a string type");
    char* s = nullptr;
    check_rc(H5Aread(attr.get(), mem.get(), &s), f, "reading " + what);
    if (s) value = s;
    H5free_memory(s);
    mem.close(f, "a datatype");
  } else {
    const std::size_t size = H5Tget_size(type.get());
    if (size == 0) fail(f, "reading the size of " + what);
    std::string buffer(size, '\0');
    check_rc(H5Aread(attr.get(), type.get(), buffer.data()), f, "reading " + what);
    value = buffer.substr(0, std::strlen(buffer.c_str()));  // drop NUL termination/padding
  }
  space.close(f, "a dataspace");
  type.close(f, "a datatype");
  attr.close(f, what);
  return value;
}

// The NAME that netCDF-4 gives a dimension that has no coordinate variable.
constexpr const char* kNetcdfDimOnly = "This is a netCDF dimension but not a netCDF variable";

// H5DSiterate_scales visitor: the dimension name of the first scale attached to an axis. The
// name is the scale's NAME attribute (set by H5DSset_scale); where that is absent or netCDF's
// placeholder, the scale dataset's own name, as netCDF itself does.
herr_t scale_name_visitor(hid_t, unsigned, hid_t scale, void* out) {
  std::string name;
  const ssize_t n = H5DSget_scale_name(scale, nullptr, 0);
  if (n < 0) return -1;
  if (n > 0) {
    std::string buffer(static_cast<std::size_t>(n) + 2, '\0');
    if (H5DSget_scale_name(scale, buffer.data(), buffer.size()) < 0) return -1;
    name = buffer.substr(0, std::strlen(buffer.c_str()));
    if (name.rfind(kNetcdfDimOnly, 0) == 0) name.clear();
  }
  if (name.empty()) {
    const ssize_t m = H5Iget_name(scale, nullptr, 0);
    if (m <= 0) return -1;
    std::string full(static_cast<std::size_t>(m) + 1, '\0');
    if (H5Iget_name(scale, full.data(), full.size()) < 0) return -1;
    full.resize(static_cast<std::size_t>(m));
    name = full.substr(full.find_last_of('/') + 1);
  }
  *static_cast<std::string*>(out) = name;
  return 1;  // stop: one dimension per axis
}

Variable read_variable(hid_t ds, const std::string& name, const H5File& f, const std::string& where) {
  Variable v;
  v.name = name;
  H5Handle space(H5Dget_space(ds), H5Sclose, f, "reading the dataspace of " + where);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) fail(f, "reading the rank of " + where);
  std::vector<hsize_t> extent(static_cast<std::size_t>(rank));
  if (rank > 0 && H5Sget_simple_extent_dims(space.get(), extent.data(), nullptr) < 0)
    fail(f, "reading the shape of " + where);
  space.close(f, "a dataspace");
  std::size_t count = 1;
  for (const hsize_t e : extent) {
    v.shape.push_back(static_cast<std::size_t>(e));
    count *= static_cast<std::size_t>(e);
  }
  v.data.resize(count);
  if (count > 0)  // HDF5 converts any stored numeric type to double
    check_rc(H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data.data()), f, "reading " + where);

  for (int a = 0; a < rank; ++a) {
    const std::string axis = "axis " + std::to_string(a) + " of " + where;
    const int scales = H5DSget_num_scales(ds, static_cast<unsigned>(a));
    if (scales < 0) fail(f, "reading the dimension scales of " + axis);
    if (scales == 0) refuse(f, axis + " has no dimension scale attached");
    std::string dim;
    if (H5DSiterate_scales(ds, static_cast<unsigned>(a), nullptr, scale_name_visitor, &dim) < 0 || dim.empty())
      fail(f, "reading the dimension name of " + axis);
    v.dims.push_back(std::move(dim));
  }

  const htri_t has_units = H5Aexists(ds, "units");
  if (has_units < 0) fail(f, "looking for the units of " + where);
  if (has_units) v.units = read_text_attribute(ds, "units", f, where);
  return v;
}

Group read_group(hid_t grp, const std::string& name, const H5File& f) {
  Group g;
  g.name = name;
  const std::string gw = "group '" + name + "'";
  for (const std::string& link : link_names(grp, f, gw)) {
    H5Handle obj(H5Oopen(grp, link.c_str(), H5P_DEFAULT), H5Oclose, f, "opening " + gw + " member '" + link + "'");
    if (H5Iget_type(obj.get()) == H5I_DATASET) {
      const htri_t is_scale = H5DSis_scale(obj.get());
      if (is_scale < 0) fail(f, "inspecting " + gw + " member '" + link + "'");
      if (!is_scale)  // scales are dimensions, recovered through the variables that use them
        g.variables.push_back(read_variable(obj.get(), link, f, gw + " variable '" + link + "'"));
    }
    obj.close(f, gw + " member '" + link + "'");
  }
  return g;
}

}  // namespace

void write_inference_data_h5(const std::string& path, const InferenceData& idata) {
  const H5File f{kFileKind, path};
  std::vector<DimList> dims;
  for (std::size_t i = 0; i < idata.groups.size(); ++i) {
    dims.push_back(group_dimensions(idata.groups[i], f));
    for (std::size_t j = 0; j < i; ++j)
      if (idata.groups[j].name == idata.groups[i].name) refuse(f, "group '" + idata.groups[i].name + "' appears twice");
  }
  write_hdf5_atomically(f, [&](const std::string& tmp) { write_file(tmp, f, idata, dims); });
}

InferenceData read_inference_data_h5(const std::string& path) {
  const H5File f{kFileKind, path};
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) refuse(f, "no such file");
  QuietHdf5Errors quiet;
  H5Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, f, "cannot open as HDF5");
  H5Handle root(H5Gopen2(file.get(), "/", H5P_DEFAULT), H5Gclose, f, "opening the root group");
  InferenceData idata;
  for (const std::string& link : link_names(root.get(), f, "the root group")) {
    H5Handle obj(H5Oopen(root.get(), link.c_str(), H5P_DEFAULT), H5Oclose, f, "opening '" + link + "'");
    if (H5Iget_type(obj.get()) == H5I_GROUP) idata.groups.push_back(read_group(obj.get(), link, f));
    obj.close(f, "'" + link + "'");
  }
  root.close(f, "the root group");
  file.close(f, "the file");
  return idata;
}

}  // namespace terracal::bayes
