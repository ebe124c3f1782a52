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

#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "core/quiet_hdf5_errors.hpp"
#include "terracal_version.hpp"

namespace terracal::bayes {
namespace {

// ---------------------------------------------------------------------------------------------
// HDF5 plumbing: error messages, handles that close themselves.

// The outermost message (what the API call failed to do) and the innermost one (why: often the
// errno text, e.g. "No such file or directory"). The middle of the stack is library internals.
std::string hdf5_error_detail() {
  std::vector<std::string> descs;
  auto collect = [](unsigned, const H5E_error2_t* e, void* out) -> herr_t {
    if (e && e->desc) static_cast<std::vector<std::string>*>(out)->emplace_back(e->desc);
    return 0;
  };
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, collect, &descs);
  H5Eclear2(H5E_DEFAULT);
  if (descs.empty()) return {};
  if (descs.size() == 1) return descs.front();
  return descs.front() + "; " + descs.back();
}

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  const std::string detail = hdf5_error_detail();
  throw RunError("InferenceData file '" + path + "': " + what + (detail.empty() ? "" : " (HDF5: " + detail + ")"));
}

hid_t check_id(hid_t id, const std::string& path, const std::string& what) {
  if (id < 0) fail(path, what);
  return id;
}

void check_rc(herr_t rc, const std::string& path, const std::string& what) {
  if (rc < 0) fail(path, what);
}

// Owns one HDF5 identifier. Normal paths call close() so that a failing close is reported;
// the destructor only cleans up after an exception.
class H5Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  H5Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  H5Handle(H5Handle&& o) noexcept : id_(std::exchange(o.id_, H5I_INVALID_HID)), closer_(o.closer_) {}
  H5Handle& operator=(H5Handle&&) = delete;
  H5Handle(const H5Handle&) = delete;
  H5Handle& operator=(const H5Handle&) = delete;
  ~H5Handle() {
    if (id_ >= 0) closer_(id_);
  }
  hid_t get() const { return id_; }
  void close(const std::string& path, const std::string& what) {
    const hid_t id = std::exchange(id_, H5I_INVALID_HID);
    check_rc(closer_(id), path, "closing " + what);
  }

 private:
  hid_t id_;
  Closer closer_;
};

H5Handle make(hid_t id, H5Handle::Closer closer, const std::string& path, const std::string& what) {
  return H5Handle(check_id(id, path, what), closer);
}

// ---------------------------------------------------------------------------------------------
// Validation: everything that can be wrong with the in-memory object is found before the file
// is created, so a bad object never produces a half-written temporary.

using DimList = std::vector<std::pair<std::string, std::size_t>>;  // in order of first use

void check_name(const std::string& name, const std::string& path, const std::string& kind) {
  if (name.empty() || name == "." || name.find('/') != std::string::npos)
    throw RunError("InferenceData file '" + path + "': invalid " + kind + " name '" + name +
                   "' (must be non-empty, without '/')");
}

DimList group_dimensions(const Group& g, const std::string& path) {
  const std::string where = "InferenceData file '" + path + "': group '" + g.name + "'";
  check_name(g.name, path, "group");
  DimList dims;
  std::map<std::string, std::size_t> length;
  std::map<std::string, std::string> first_user;  // which variable fixed a dimension's length
  for (const Variable& v : g.variables) {
    check_name(v.name, path, "variable");
    const std::string var_where = where + ", variable '" + v.name + "'";
    if (v.dims.size() != v.shape.size())
      throw RunError(var_where + ": " + std::to_string(v.dims.size()) + " dimension names but shape has " +
                     std::to_string(v.shape.size()) + " entries");
    std::size_t count = 1;
    for (std::size_t a = 0; a < v.dims.size(); ++a) {
      const std::string& d = v.dims[a];
      check_name(d, path, "dimension");
      if (v.shape[a] == 0) throw RunError(var_where + ": dimension '" + d + "' has length 0");
      for (std::size_t b = 0; b < a; ++b)
        if (v.dims[b] == d)  // xarray cannot index a repeated dimension; use e.g. p_dim_0, p_dim_1
          throw RunError(var_where + ": dimension '" + d + "' is used twice");
      auto [it, inserted] = length.emplace(d, v.shape[a]);
      if (inserted) {
        dims.emplace_back(d, v.shape[a]);
        first_user[d] = v.name;
      } else if (it->second != v.shape[a]) {
        throw RunError(var_where + ": dimension '" + d + "' has length " + std::to_string(v.shape[a]) + " but length " +
                       std::to_string(it->second) + " in variable '" + first_user[d] + "'");
      }
      count *= v.shape[a];
    }
    if (v.data.size() != count)
      throw RunError(var_where + ": shape holds " + std::to_string(count) + " values but data has " +
                     std::to_string(v.data.size()));
  }
  // Dimension scales and variables share the group's namespace.
  for (std::size_t i = 0; i < g.variables.size(); ++i) {
    const std::string& n = g.variables[i].name;
    if (length.count(n)) throw RunError(where + ": variable '" + n + "' has the name of a dimension");
    for (std::size_t j = 0; j < i; ++j)
      if (g.variables[j].name == n) throw RunError(where + ": variable '" + n + "' appears twice");
  }
  return dims;
}

// ---------------------------------------------------------------------------------------------
// Writing

// Creation-order tracking is what netCDF-4 sets on every group and object: readers then list
// variables and attributes in the order written, and netCDF may reopen the file for writing.
constexpr unsigned kCreationOrder = H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED;

// Object creation property list without modification/creation times, so files are reproducible.
H5Handle timeless_plist(hid_t cls, const std::string& path) {
  H5Handle p = make(H5Pcreate(cls), H5Pclose, path, "creating a property list");
  check_rc(H5Pset_obj_track_times(p.get(), 0), path, "disabling object time tracking");
  check_rc(H5Pset_attr_creation_order(p.get(), kCreationOrder), path, "tracking attribute order");
  if (cls != H5P_DATASET_CREATE)
    check_rc(H5Pset_link_creation_order(p.get(), kCreationOrder), path, "tracking link order");
  return p;
}

// A scalar fixed-length ASCII string attribute: what netCDF-4 writes for a text (NC_CHAR) attribute.
void write_text_attribute(hid_t loc, const std::string& name, const std::string& value, const std::string& path) {
  const std::string what = "attribute '" + name + "'";
  H5Handle type = make(H5Tcopy(H5T_C_S1), H5Tclose, path, "creating the string type of " + what);
  check_rc(H5Tset_size(type.get(), value.empty() ? 1 : value.size()), path, "sizing " + what);
  check_rc(H5Tset_strpad(type.get(), H5T_STR_NULLTERM), path, "setting the padding of " + what);
  H5Handle space = make(H5Screate(H5S_SCALAR), H5Sclose, path, "creating the dataspace of " + what);
  H5Handle attr = make(H5Acreate2(loc, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose, path,
                       "creating " + what);
  std::string buffer = value;
  buffer.resize(value.empty() ? 1 : value.size(), '\0');
  check_rc(H5Awrite(attr.get(), type.get(), buffer.data()), path, "writing " + what);
  attr.close(path, what);
  space.close(path, "a dataspace");
  type.close(path, "a datatype");
}

void write_library_attributes(hid_t loc, const std::string& path) {
  write_text_attribute(loc, "inference_library", "terracal", path);
  write_text_attribute(loc, "inference_library_version", TERRACAL_VERSION, path);
}

H5Handle create_dataset(hid_t group, const std::string& name, hid_t file_type, const std::vector<hsize_t>& extent,
                        hid_t dcpl, const std::string& path, const std::string& what) {
  H5Handle space = extent.empty() ? make(H5Screate(H5S_SCALAR), H5Sclose, path, "creating the dataspace of " + what)
                                  : make(H5Screate_simple(static_cast<int>(extent.size()), extent.data(), nullptr),
                                         H5Sclose, path, "creating the dataspace of " + what);
  H5Handle ds = make(H5Dcreate2(group, name.c_str(), file_type, space.get(), H5P_DEFAULT, dcpl, H5P_DEFAULT), H5Dclose,
                     path, "creating " + what);
  space.close(path, "a dataspace");
  return ds;
}

void write_group(hid_t file, const Group& g, const DimList& dims, hid_t gcpl, hid_t dcpl, const std::string& path) {
  const std::string gw = "group '" + g.name + "'";
  H5Handle grp =
      make(H5Gcreate2(file, g.name.c_str(), H5P_DEFAULT, gcpl, H5P_DEFAULT), H5Gclose, path, "creating " + gw);
  write_library_attributes(grp.get(), path);

  // Dimension scales first (netCDF-4 defines dimensions before the variables using them):
  // ArviZ-style integer coordinates 0..n-1, named by H5DSset_scale so readers see a coordinate
  // variable (a NAME of "This is a netCDF dimension but not a netCDF variable" would hide it).
  std::map<std::string, H5Handle> scales;
  for (const auto& [dim, n] : dims) {
    const std::string what = gw + " dimension '" + dim + "'";
    H5Handle ds = create_dataset(grp.get(), dim, H5T_STD_I64LE, {static_cast<hsize_t>(n)}, dcpl, path, what);
    std::vector<std::int64_t> index(n);
    std::iota(index.begin(), index.end(), std::int64_t{0});
    check_rc(H5Dwrite(ds.get(), H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, index.data()), path,
             "writing " + what);
    check_rc(H5DSset_scale(ds.get(), dim.c_str()), path, "making " + what + " a dimension scale");
    scales.emplace(dim, std::move(ds));
  }

  for (const Variable& v : g.variables) {
    const std::string what = gw + " variable '" + v.name + "'";
    const std::vector<hsize_t> extent(v.shape.begin(), v.shape.end());
    H5Handle ds = create_dataset(grp.get(), v.name, H5T_IEEE_F64LE, extent, dcpl, path, what);
    check_rc(H5Dwrite(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data.data()), path,
             "writing " + what);
    for (std::size_t a = 0; a < v.dims.size(); ++a)
      check_rc(H5DSattach_scale(ds.get(), scales.at(v.dims[a]).get(), static_cast<unsigned>(a)), path,
               "attaching dimension '" + v.dims[a] + "' to axis " + std::to_string(a) + " of " + what);
    if (!v.units.empty()) write_text_attribute(ds.get(), "units", v.units, path);
    ds.close(path, what);
  }
  for (auto& [dim, ds] : scales) ds.close(path, gw + " dimension '" + dim + "'");
  grp.close(path, gw);
}

void write_file(const std::string& tmp, const std::string& path, const InferenceData& idata,
                const std::vector<DimList>& dims) {
  // Root group: its creation properties live in the file creation property list.
  H5Handle fcpl = timeless_plist(H5P_FILE_CREATE, path);
  H5Handle fapl = make(H5Pcreate(H5P_FILE_ACCESS), H5Pclose, path, "creating a file access property list");
  // The oldest object formats that can hold these features (as netCDF-4 does), so that readers
  // built on HDF5 1.8 open the file too.
  check_rc(H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_EARLIEST, H5F_LIBVER_V18), path, "setting format bounds");
  H5Handle gcpl = timeless_plist(H5P_GROUP_CREATE, path);
  H5Handle dcpl = timeless_plist(H5P_DATASET_CREATE, path);

  H5Handle file = make(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, fcpl.get(), fapl.get()), H5Fclose, path,
                       "cannot create temporary file '" + tmp + "'");
  write_library_attributes(file.get(), path);
  for (std::size_t i = 0; i < idata.groups.size(); ++i)
    write_group(file.get(), idata.groups[i], dims[i], gcpl.get(), dcpl.get(), path);
  check_rc(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), path, "flushing '" + tmp + "'");
  file.close(path, "'" + tmp + "'");
  dcpl.close(path, "a property list");
  gcpl.close(path, "a property list");
  fapl.close(path, "a property list");
  fcpl.close(path, "a property list");
}

// ---------------------------------------------------------------------------------------------
// Reading

// Link names of a group in creation order where tracked (files written here, by netCDF), else
// by name (files written by tools that do not track order, e.g. plain h5py).
std::vector<std::string> link_names(hid_t group, const std::string& path, const std::string& where) {
  H5Handle gcpl = make(H5Gget_create_plist(group), H5Pclose, path, "reading the creation properties of " + where);
  unsigned flags = 0;
  check_rc(H5Pget_link_creation_order(gcpl.get(), &flags), path, "reading the link order of " + where);
  gcpl.close(path, "a property list");
  const H5_index_t index = (flags & H5P_CRT_ORDER_TRACKED) ? H5_INDEX_CRT_ORDER : H5_INDEX_NAME;

  H5G_info_t info;
  check_rc(H5Gget_info(group, &info), path, "listing " + where);
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t n = H5Lget_name_by_idx(group, ".", index, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (n < 0) fail(path, "reading a link name in " + where);
    std::string name(static_cast<std::size_t>(n) + 1, '\0');
    if (H5Lget_name_by_idx(group, ".", index, H5_ITER_INC, i, name.data(), name.size(), H5P_DEFAULT) < 0)
      fail(path, "reading a link name in " + where);
    name.resize(static_cast<std::size_t>(n));
    names.push_back(std::move(name));
  }
  return names;
}

// Scalar string attribute, fixed-length (netCDF NC_CHAR, what we write) or variable-length
// (netCDF NC_STRING, what h5py writes).
std::string read_text_attribute(hid_t loc, const std::string& name, const std::string& path, const std::string& where) {
  const std::string what = "attribute '" + name + "' of " + where;
  H5Handle attr = make(H5Aopen(loc, name.c_str(), H5P_DEFAULT), H5Aclose, path, "opening " + what);
  H5Handle type = make(H5Aget_type(attr.get()), H5Tclose, path, "reading the type of " + what);
  if (H5Tget_class(type.get()) != H5T_STRING)
    throw RunError("InferenceData file '" + path + "': " + what + " is not text");
  H5Handle space = make(H5Aget_space(attr.get()), H5Sclose, path, "reading the dataspace of " + what);
  if (H5Sget_simple_extent_npoints(space.get()) != 1)
    throw RunError("InferenceData file '" + path + "': " + what + " is not a single string");
  const htri_t variable = H5Tis_variable_str(type.get());
  if (variable < 0) fail(path, "reading the type of " + what);
  std::string value;
  if (variable) {
    H5Handle mem = make(H5Tcopy(H5T_C_S1), H5Tclose, path, "creating a string type");
    check_rc(H5Tset_size(mem.get(), H5T_VARIABLE), path, "creating a string type");
    check_rc(H5Tset_cset(mem.get(), H5Tget_cset(type.get())), path, "creating a string type");
    char* s = nullptr;
    check_rc(H5Aread(attr.get(), mem.get(), &s), path, "reading " + what);
    if (s) value = s;
    H5free_memory(s);
    mem.close(path, "a datatype");
  } else {
    const std::size_t size = H5Tget_size(type.get());
    if (size == 0) fail(path, "reading the size of " + what);
    std::string buffer(size, '\0');
    check_rc(H5Aread(attr.get(), type.get(), buffer.data()), path, "reading " + what);
    value = buffer.substr(0, std::strlen(buffer.c_str()));  // drop NUL termination/padding
  }
  space.close(path, "a dataspace");
  type.close(path, "a datatype");
  attr.close(path, what);
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

Variable read_variable(hid_t ds, const std::string& name, const std::string& path, const std::string& where) {
  Variable v;
  v.name = name;
  H5Handle space = make(H5Dget_space(ds), H5Sclose, path, "reading the dataspace of " + where);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) fail(path, "reading the rank of " + where);
  std::vector<hsize_t> extent(static_cast<std::size_t>(rank));
  if (rank > 0 && H5Sget_simple_extent_dims(space.get(), extent.data(), nullptr) < 0)
    fail(path, "reading the shape of " + where);
  space.close(path, "a dataspace");
  std::size_t count = 1;
  for (const hsize_t e : extent) {
    v.shape.push_back(static_cast<std::size_t>(e));
    count *= static_cast<std::size_t>(e);
  }
  v.data.resize(count);
  if (count > 0)  // HDF5 converts any stored numeric type to double
    check_rc(H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data.data()), path, "reading " + where);

  for (int a = 0; a < rank; ++a) {
    const std::string axis = "axis " + std::to_string(a) + " of " + where;
    const int scales = H5DSget_num_scales(ds, static_cast<unsigned>(a));
    if (scales < 0) fail(path, "reading the dimension scales of " + axis);
    if (scales == 0) throw RunError("InferenceData file '" + path + "': " + axis + " has no dimension scale attached");
    std::string dim;
    if (H5DSiterate_scales(ds, static_cast<unsigned>(a), nullptr, scale_name_visitor, &dim) < 0 || dim.empty())
      fail(path, "reading the dimension name of " + axis);
    v.dims.push_back(std::move(dim));
  }

  const htri_t has_units = H5Aexists(ds, "units");
  if (has_units < 0) fail(path, "looking for the units of " + where);
  if (has_units) v.units = read_text_attribute(ds, "units", path, where);
  return v;
}

Group read_group(hid_t grp, const std::string& name, const std::string& path) {
  Group g;
  g.name = name;
  const std::string gw = "group '" + name + "'";
  for (const std::string& link : link_names(grp, path, gw)) {
    H5Handle obj =
        make(H5Oopen(grp, link.c_str(), H5P_DEFAULT), H5Oclose, path, "opening " + gw + " member '" + link + "'");
    if (H5Iget_type(obj.get()) == H5I_DATASET) {
      const htri_t is_scale = H5DSis_scale(obj.get());
      if (is_scale < 0) fail(path, "inspecting " + gw + " member '" + link + "'");
      if (!is_scale)  // scales are dimensions, recovered through the variables that use them
        g.variables.push_back(read_variable(obj.get(), link, path, gw + " variable '" + link + "'"));
    }
    obj.close(path, gw + " member '" + link + "'");
  }
  return g;
}

}  // namespace

void write_inference_data_h5(const std::string& path, const InferenceData& idata) {
  std::vector<DimList> dims;
  for (std::size_t i = 0; i < idata.groups.size(); ++i) {
    dims.push_back(group_dimensions(idata.groups[i], path));
    for (std::size_t j = 0; j < i; ++j)
      if (idata.groups[j].name == idata.groups[i].name)
        throw RunError("InferenceData file '" + path + "': group '" + idata.groups[i].name + "' appears twice");
  }

  const std::string tmp = temporary_path_for(path);
  QuietHdf5Errors quiet;
  try {
    write_file(tmp, path, idata, dims);  // every HDF5 handle is closed when this returns or throws
    commit_file(tmp, path);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw;
  }
}

InferenceData read_inference_data_h5(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw RunError("InferenceData file '" + path + "': no such file");
  QuietHdf5Errors quiet;
  H5Handle file = make(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, path, "cannot open as HDF5");
  H5Handle root = make(H5Gopen2(file.get(), "/", H5P_DEFAULT), H5Gclose, path, "opening the root group");
  InferenceData idata;
  for (const std::string& link : link_names(root.get(), path, "the root group")) {
    H5Handle obj = make(H5Oopen(root.get(), link.c_str(), H5P_DEFAULT), H5Oclose, path, "opening '" + link + "'");
    if (H5Iget_type(obj.get()) == H5I_GROUP) idata.groups.push_back(read_group(obj.get(), link, path));
    obj.close(path, "'" + link + "'");
  }
  root.close(path, "the root group");
  file.close(path, "the file");
  return idata;
}

}  // namespace terracal::bayes
