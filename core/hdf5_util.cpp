#include "core/hdf5_util.hpp"

#include <filesystem>
#include <system_error>
#include <utility>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "core/quiet_hdf5_errors.hpp"

namespace terracal {
namespace {

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

}  // namespace

void fail(const H5File& file, const std::string& what) {
  const std::string detail = hdf5_error_detail();
  refuse(file, what + (detail.empty() ? "" : " (HDF5: " + detail + ")"));
}

void refuse(const H5File& file, const std::string& what) {
  throw RunError(file.kind + " '" + file.path + "': " + what);
}

void check_rc(herr_t rc, const H5File& file, const std::string& what) {
  if (rc < 0) fail(file, what);
}

H5Handle::H5Handle(hid_t id, Closer closer, const H5File& file, const std::string& what) : id_(id), closer_(closer) {
  if (id_ < 0) fail(file, what);
}

H5Handle::H5Handle(H5Handle&& o) noexcept : id_(std::exchange(o.id_, H5I_INVALID_HID)), closer_(o.closer_) {}

H5Handle::~H5Handle() {
  if (id_ >= 0) closer_(id_);
}

void H5Handle::close(const H5File& file, const std::string& what) {
  const hid_t id = std::exchange(id_, H5I_INVALID_HID);
  check_rc(closer_(id), file, "closing " + what);
}

H5Handle timeless_plist(hid_t cls, const H5File& file) {
  H5Handle p(H5Pcreate(cls), H5Pclose, file, "creating a property list");
  check_rc(H5Pset_obj_track_times(p.get(), 0), file, "disabling object time tracking");
  constexpr unsigned order = H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED;
  check_rc(H5Pset_attr_creation_order(p.get(), order), file, "tracking attribute order");
  if (cls != H5P_DATASET_CREATE) check_rc(H5Pset_link_creation_order(p.get(), order), file, "tracking link order");
  return p;
}

void write_text_attribute(hid_t loc, const std::string& name, const std::string& value, const H5File& file) {
  const std::string what = "attribute '" + name + "'";
  H5Handle type(H5Tcopy(H5T_C_S1), H5Tclose, file, "creating the string type of " + what);
  check_rc(H5Tset_size(type.get(), value.empty() ? 1 : value.size()), file, "sizing " + what);
  check_rc(H5Tset_strpad(type.get(), H5T_STR_NULLTERM), file, "setting the padding of " + what);
  H5Handle space(H5Screate(H5S_SCALAR), H5Sclose, file, "creating the dataspace of " + what);
  H5Handle attr(H5Acreate2(loc, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose, file,
                "creating " + what);
  std::string buffer = value;
  buffer.resize(value.empty() ? 1 : value.size(), '\0');
  check_rc(H5Awrite(attr.get(), type.get(), buffer.data()), file, "writing " + what);
  attr.close(file, what);
  space.close(file, "a dataspace");
  type.close(file, "a datatype");
}

void write_number_attribute(hid_t loc, const std::string& name, hid_t file_type, hid_t mem_type, const void* value,
                            const H5File& file) {
  const std::string what = "attribute '" + name + "'";
  H5Handle space(H5Screate(H5S_SCALAR), H5Sclose, file, "creating the dataspace of " + what);
  H5Handle attr(H5Acreate2(loc, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose, file,
                "creating " + what);
  check_rc(H5Awrite(attr.get(), mem_type, value), file, "writing " + what);
  attr.close(file, what);
  space.close(file, "a dataspace");
}

H5Handle create_group(hid_t loc, const std::string& name, hid_t gcpl, const H5File& file) {
  return H5Handle(H5Gcreate2(loc, name.c_str(), H5P_DEFAULT, gcpl, H5P_DEFAULT), H5Gclose, file,
                  "creating group '" + name + "'");
}

H5Handle create_dataset(hid_t loc, const std::string& name, hid_t file_type, const std::vector<hsize_t>& extent,
                        hid_t dcpl, const H5File& file, const std::string& what) {
  const std::string space_what = "creating the dataspace of " + what;
  H5Handle space = extent.empty() ? H5Handle(H5Screate(H5S_SCALAR), H5Sclose, file, space_what)
                                  : H5Handle(H5Screate_simple(static_cast<int>(extent.size()), extent.data(), nullptr),
                                             H5Sclose, file, space_what);
  H5Handle ds(H5Dcreate2(loc, name.c_str(), file_type, space.get(), H5P_DEFAULT, dcpl, H5P_DEFAULT), H5Dclose, file,
              "creating " + what);
  space.close(file, "a dataspace");
  return ds;
}

void check_object_name(const std::string& name, const H5File& file, const std::string& role) {
  if (name.empty() || name == "." || name.find('/') != std::string::npos)
    refuse(file, "invalid " + role + " name '" + name + "' (must be non-empty, without '/')");
}

void write_hdf5_atomically(const H5File& file, const std::function<void(const std::string& tmp)>& write) {
  const std::string tmp = temporary_path_for(file.path);
  QuietHdf5Errors quiet;
  try {
    write(tmp);
    commit_file(tmp, file.path);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw;
  }
}

}  // namespace terracal
