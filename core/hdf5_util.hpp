#pragma once
// The HDF5 plumbing shared by our HDF5 writers and readers: errors that name the file and what
// failed (with HDF5's own reason), identifiers that close themselves, reproducible creation
// properties, scalar attributes, and the atomic write of a whole file.
#include <hdf5.h>

#include <functional>
#include <string>
#include <vector>

namespace terracal {

// The file that messages are about: they read "<kind> '<path>': <what>", e.g.
// "batch file 'out/batch.h5': creating group 'summary' (HDF5: ...)". Names the file; opens nothing.
struct H5File {
  std::string kind;  // e.g. "InferenceData file", "batch file"
  std::string path;  // the final path the user gave, also while a temporary is being written
};

// Throws RunError naming the file and `what`, followed by the outermost and innermost messages of
// HDF5's error stack (what the API call failed to do, and why), which it clears.
[[noreturn]] void fail(const H5File& file, const std::string& what);

// Throws RunError naming the file and `what`: for problems found without an HDF5 call failing.
[[noreturn]] void refuse(const H5File& file, const std::string& what);

// fail(file, what) when an HDF5 call returned a negative status.
void check_rc(herr_t rc, const H5File& file, const std::string& what);

// Owns one HDF5 identifier. Normal paths call close() so that a failing close is reported;
// the destructor only cleans up after an exception.
class H5Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  // Takes `id` as returned by the call that made it: fail(file, what) when that call failed.
  H5Handle(hid_t id, Closer closer, const H5File& file, const std::string& what);
  H5Handle(H5Handle&& o) noexcept;
  H5Handle& operator=(H5Handle&&) = delete;
  H5Handle(const H5Handle&) = delete;
  H5Handle& operator=(const H5Handle&) = delete;
  ~H5Handle();
  hid_t get() const { return id_; }
  // Fails with "closing <what>".
  void close(const H5File& file, const std::string& what);

 private:
  hid_t id_;
  Closer closer_;
};

// A creation property list of class `cls` (H5P_FILE_CREATE, H5P_GROUP_CREATE, H5P_DATASET_CREATE)
// without modification/creation times, so that writing the same content twice gives identical
// bytes, and with creation order tracked, so that readers list links and attributes in the order
// written (netCDF-4 sets this on every object, and may then reopen the file for writing).
H5Handle timeless_plist(hid_t cls, const H5File& file);

// A scalar fixed-length ASCII string attribute: what netCDF-4 writes for a text (NC_CHAR) attribute.
void write_text_attribute(hid_t loc, const std::string& name, const std::string& value, const H5File& file);

// A scalar number attribute stored as `file_type` (e.g. H5T_STD_I64LE), given in memory as
// `mem_type` (e.g. H5T_NATIVE_INT64) at `value`.
void write_number_attribute(hid_t loc, const std::string& name, hid_t file_type, hid_t mem_type, const void* value,
                            const H5File& file);

// Group `name` in `loc`, created with `gcpl` (fails with "creating group '<name>'").
H5Handle create_group(hid_t loc, const std::string& name, hid_t gcpl, const H5File& file);

// Dataset `name` in `loc` of `file_type` and shape `extent` (scalar when empty), created with
// `dcpl`; `what` names it in messages.
H5Handle create_dataset(hid_t loc, const std::string& name, hid_t file_type, const std::vector<hsize_t>& extent,
                        hid_t dcpl, const H5File& file, const std::string& what);

// Refuses a group, dataset or dimension name (`role`) that HDF5 would read as a path.
void check_object_name(const std::string& name, const H5File& file, const std::string& role);

// Calls write(tmp) to write the whole file under a temporary name, with HDF5's printing of errors
// off, then commits it to file.path (core/atomic_file.hpp). `write` must have closed every HDF5
// handle on the temporary when it returns or throws; on any failure the temporary is removed.
void write_hdf5_atomically(const H5File& file, const std::function<void(const std::string& tmp)>& write);

}  // namespace terracal
