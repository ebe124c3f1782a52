#include "rom/batch_h5.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <utility>
#include <vector>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "core/quiet_hdf5_errors.hpp"

namespace terracal::rom {
namespace {

// --- HDF5 plumbing (as bayes/posterior_h5.cpp): messages naming the file, self-closing handles --

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
  throw RunError("batch file '" + path + "': " + what + (detail.empty() ? "" : " (HDF5: " + detail + ")"));
}

[[noreturn]] void refuse(const std::string& path, const std::string& what) {
  throw RunError("batch file '" + path + "': " + what);
}

void check_rc(herr_t rc, const std::string& path, const std::string& what) {
  if (rc < 0) fail(path, what);
}

class H5Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  H5Handle(hid_t id, Closer closer, const std::string& path, const std::string& what) : id_(id), closer_(closer) {
    if (id_ < 0) fail(path, what);
  }
  H5Handle(H5Handle&& o) noexcept : id_(std::exchange(o.id_, H5I_INVALID_HID)), closer_(o.closer_) {}
  H5Handle& operator=(H5Handle&&) = delete;
  H5Handle(const H5Handle&) = delete;
  H5Handle& operator=(const H5Handle&) = delete;
  ~H5Handle() {
    if (id_ >= 0) closer_(id_);
  }
  hid_t get() const { return id_; }
  // Normal paths close explicitly, so that a failing close is reported.
  void close(const std::string& path, const std::string& what) {
    const hid_t id = std::exchange(id_, H5I_INVALID_HID);
    check_rc(closer_(id), path, "closing " + what);
  }

 private:
  hid_t id_;
  Closer closer_;
};

// Property lists without modification/creation times, so that files are reproducible.
H5Handle timeless_plist(hid_t cls, const std::string& path) {
  H5Handle p(H5Pcreate(cls), H5Pclose, path, "creating a property list");
  check_rc(H5Pset_obj_track_times(p.get(), 0), path, "disabling object time tracking");
  constexpr unsigned order = H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED;
  check_rc(H5Pset_attr_creation_order(p.get(), order), path, "tracking attribute order");
  if (cls != H5P_DATASET_CREATE) check_rc(H5Pset_link_creation_order(p.get(), order), path, "tracking link order");
  return p;
}

struct Ctx {
  std::string path;
  hid_t gcpl = H5I_INVALID_HID;
  hid_t dcpl = H5I_INVALID_HID;
};

void text_attribute(hid_t loc, const std::string& name, const std::string& value, const Ctx& c) {
  const std::string what = "attribute '" + name + "'";
  H5Handle type(H5Tcopy(H5T_C_S1), H5Tclose, c.path, "creating the string type of " + what);
  check_rc(H5Tset_size(type.get(), value.empty() ? 1 : value.size()), c.path, "sizing " + what);
  check_rc(H5Tset_strpad(type.get(), H5T_STR_NULLTERM), c.path, "setting the padding of " + what);
  H5Handle space(H5Screate(H5S_SCALAR), H5Sclose, c.path, "creating the dataspace of " + what);
  H5Handle attr(H5Acreate2(loc, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose, c.path,
                "creating " + what);
  std::string buffer = value;
  buffer.resize(value.empty() ? 1 : value.size(), '\0');
  check_rc(H5Awrite(attr.get(), type.get(), buffer.data()), c.path, "writing " + what);
  attr.close(c.path, what);
}

// A scalar number attribute stored as `file_type`, given in memory as `mem_type`.
void number_attribute(hid_t loc, const std::string& name, hid_t file_type, hid_t mem_type, const void* value,
                      const Ctx& c) {
  const std::string what = "attribute '" + name + "'";
  H5Handle space(H5Screate(H5S_SCALAR), H5Sclose, c.path, "creating the dataspace of " + what);
  H5Handle attr(H5Acreate2(loc, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose, c.path,
                "creating " + what);
  check_rc(H5Awrite(attr.get(), mem_type, value), c.path, "writing " + what);
  attr.close(c.path, what);
}

void double_attribute(hid_t loc, const std::string& name, double v, const Ctx& c) {
  number_attribute(loc, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &v, c);
}

H5Handle make_group(hid_t file, const std::string& name, const Ctx& c) {
  return H5Handle(H5Gcreate2(file, name.c_str(), H5P_DEFAULT, c.gcpl, H5P_DEFAULT), H5Gclose, c.path,
                  "creating group '" + name + "'");
}

H5Handle make_dataset(hid_t loc, const std::string& name, const std::vector<hsize_t>& extent, const Ctx& c,
                      const std::string& what) {
  H5Handle space(H5Screate_simple(static_cast<int>(extent.size()), extent.data(), nullptr), H5Sclose, c.path,
                 "creating the dataspace of " + what);
  H5Handle ds(H5Dcreate2(loc, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, c.dcpl, H5P_DEFAULT), H5Dclose,
              c.path, "creating " + what);
  space.close(c.path, "a dataspace");
  return ds;
}

// A 1-D float64 dataset of n values (units: attribute "units" unless empty).
void write_vector(hid_t loc, const std::string& name, const double* data, std::size_t n, const std::string& units,
                  const Ctx& c, const std::string& what) {
  H5Handle ds = make_dataset(loc, name, {static_cast<hsize_t>(n)}, c, what);
  if (n > 0)
    check_rc(H5Dwrite(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), c.path, "writing " + what);
  if (!units.empty()) text_attribute(ds.get(), "units", units, c);
  ds.close(c.path, what);
}

// src holds [a][v] (a < na, v < nv); the dataset gets [v][a]. Transposed a block of vehicles at a
// time, so that a batch of millions of vehicles needs no second full copy in memory.
void write_transposed(hid_t loc, const std::string& name, const double* src, std::size_t na, std::size_t nv,
                      const std::string& units, const Ctx& c, const std::string& what) {
  H5Handle ds = make_dataset(loc, name, {static_cast<hsize_t>(nv), static_cast<hsize_t>(na)}, c, what);
  if (na > 0 && nv > 0) {
    constexpr std::size_t kBlockValues = std::size_t{1} << 23;  // 64 MiB of doubles
    const std::size_t block = std::max<std::size_t>(1, std::min(nv, kBlockValues / na));
    std::vector<double> buffer(block * na);
    H5Handle file_space(H5Dget_space(ds.get()), H5Sclose, c.path, "reading the dataspace of " + what);
    for (std::size_t v0 = 0; v0 < nv; v0 += block) {
      const std::size_t nb = std::min(block, nv - v0);
      for (std::size_t a = 0; a < na; ++a) {
        const double* row = src + a * nv + v0;
        for (std::size_t v = 0; v < nb; ++v) buffer[v * na + a] = row[v];
      }
      const hsize_t start[2] = {static_cast<hsize_t>(v0), 0};
      const hsize_t count[2] = {static_cast<hsize_t>(nb), static_cast<hsize_t>(na)};
      check_rc(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr), c.path,
               "selecting rows of " + what);
      H5Handle mem_space(H5Screate_simple(2, count, nullptr), H5Sclose, c.path, "creating a memory dataspace");
      check_rc(H5Dwrite(ds.get(), H5T_NATIVE_DOUBLE, mem_space.get(), file_space.get(), H5P_DEFAULT, buffer.data()),
               c.path, "writing " + what);
      mem_space.close(c.path, "a dataspace");
    }
    file_space.close(c.path, "a dataspace");
  }
  if (!units.empty()) text_attribute(ds.get(), "units", units, c);
  ds.close(c.path, what);
}

// Units by name (a name missing here, e.g. one added to rom_batch.hpp later, gets none).
std::string channel_units(const std::string& name) {
  static const std::pair<const char*, const char*> table[] = {{"x", "m"},      {"y", "m"},      {"yaw", "rad"},
                                                              {"vx", "m/s"},   {"vy", "m/s"},   {"yaw_rate", "rad/s"},
                                                              {"ax", "m/s^2"}, {"ay", "m/s^2"}, {"roll", "rad"}};
  for (const auto& [n, u] : table)
    if (name == n) return u;
  return {};
}

std::string metric_units(const std::string& name) {
  static const std::pair<const char*, const char*> table[] = {{"final_x", "m"},        {"final_y", "m"},
                                                              {"final_yaw", "rad"},    {"final_vx", "m/s"},
                                                              {"max_abs_ay", "m/s^2"}, {"max_abs_yaw_rate", "rad/s"},
                                                              {"max_abs_roll", "rad"}, {"failed_at", "s"}};
  for (const auto& [n, u] : table)
    if (name == n) return u;
  return {};
}

void check_name(const std::string& name, const std::string& path, const std::string& kind) {
  if (name.empty() || name == "." || name.find('/') != std::string::npos)
    refuse(path, "invalid " + kind + " name '" + name + "' (must be non-empty, without '/')");
}

// Everything that can be wrong with the inputs is found before the file is created.
void check_inputs(const std::string& path, const BatchResult& r, const BatchOptions& o, const VaryDraws* draws) {
  if (r.vehicles < 0 || r.samples < 0 || r.states < 0)
    refuse(path, "negative count (vehicles " + std::to_string(r.vehicles) + ", samples " + std::to_string(r.samples) +
                     ", states " + std::to_string(r.states) + ")");
  const std::size_t nv = static_cast<std::size_t>(r.vehicles), ns = static_cast<std::size_t>(r.samples);
  auto sized = [&](const std::vector<double>& v, std::size_t want, const std::string& what) {
    if (v.size() != want)
      refuse(path, what + " holds " + std::to_string(v.size()) + " values, expected " + std::to_string(want));
  };
  sized(r.metrics, static_cast<std::size_t>(kBatchMetricCount) * nv, "the summary metrics");
  sized(r.channels, o.channels.size() * ns * nv, "the channels");
  sized(r.final_state, static_cast<std::size_t>(r.states) * nv, "the final state");
  for (std::size_t i = 0; i < o.channels.size(); ++i) {
    if (o.channels[i] < 0 || o.channels[i] >= kBatchChannelCount)
      refuse(path, "channel number " + std::to_string(static_cast<int>(o.channels[i])) + " is unknown");
    for (std::size_t j = 0; j < i; ++j)
      if (o.channels[j] == o.channels[i])
        refuse(path, std::string("channel '") + kBatchChannelNames[o.channels[i]] + "' is listed twice");
  }
  if (ns > 0 && !(o.output_rate > 0))
    refuse(path, "samples without a positive output rate (" + std::to_string(o.output_rate) + ")");
  if (!draws) return;
  if (draws->values.size() != draws->names.size())
    refuse(path, "the draws have " + std::to_string(draws->names.size()) + " names but " +
                     std::to_string(draws->values.size()) + " value lists");
  for (std::size_t p = 0; p < draws->names.size(); ++p) {
    check_name(draws->names[p], path, "parameter");
    for (std::size_t q = 0; q < p; ++q)
      if (draws->names[q] == draws->names[p]) refuse(path, "parameter '" + draws->names[p] + "' appears twice");
    if (draws->values[p].size() != nv)
      refuse(path, "parameter '" + draws->names[p] + "' has " + std::to_string(draws->values[p].size()) +
                       " values for " + std::to_string(nv) + " vehicles");
  }
}

void write_file(const std::string& tmp, const BatchResult& r, const BatchOptions& o, const VaryDraws* draws,
                const BatchH5Info& info, Ctx& c) {
  H5Handle fcpl = timeless_plist(H5P_FILE_CREATE, c.path);
  H5Handle gcpl = timeless_plist(H5P_GROUP_CREATE, c.path);
  H5Handle dcpl = timeless_plist(H5P_DATASET_CREATE, c.path);
  c.gcpl = gcpl.get();
  c.dcpl = dcpl.get();
  H5Handle file(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, fcpl.get(), H5P_DEFAULT), H5Fclose, c.path,
                "cannot create temporary file '" + tmp + "'");
  const hid_t root = file.get();
  const std::size_t nv = static_cast<std::size_t>(r.vehicles), ns = static_cast<std::size_t>(r.samples);

  text_attribute(root, "model", info.model.empty() ? std::string(model_name(o.model)) : info.model, c);
  text_attribute(root, "vehicle", info.vehicle, c);
  double_attribute(root, "step", o.step, c);
  double_attribute(root, "end_time", o.end_time, c);
  double_attribute(root, "initial_speed", o.initial_speed, c);
  double_attribute(root, "output_rate", o.output_rate, c);
  const std::int64_t vehicles = r.vehicles, failed = r.failed;
  number_attribute(root, "vehicles", H5T_STD_I64LE, H5T_NATIVE_INT64, &vehicles, c);
  number_attribute(root, "failed", H5T_STD_I64LE, H5T_NATIVE_INT64, &failed, c);
  const std::uint64_t seed = info.seed;
  number_attribute(root, "seed", H5T_STD_U64LE, H5T_NATIVE_UINT64, &seed, c);
  text_attribute(root, "device", r.device, c);

  std::vector<double> time(ns);
  for (std::size_t k = 0; k < ns; ++k) time[k] = static_cast<double>(k) / o.output_rate;
  write_vector(root, "time", time.data(), ns, "s", c, "dataset 'time'");

  H5Handle params = make_group(root, "parameters", c);
  if (draws) {
    for (std::size_t p = 0; p < draws->names.size(); ++p) {
      const std::string& name = draws->names[p];
      const std::string what = "dataset 'parameters/" + name + "'";
      H5Handle ds = make_dataset(params.get(), name, {static_cast<hsize_t>(nv)}, c, what);
      if (nv > 0)
        check_rc(H5Dwrite(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, draws->values[p].data()), c.path,
                 "writing " + what);
      if (draws->units.size() == draws->names.size()) text_attribute(ds.get(), "units", draws->units[p], c);
      if (draws->distributions.size() == draws->names.size())
        text_attribute(ds.get(), "distribution", draws->distributions[p], c);
      ds.close(c.path, what);
    }
  }
  params.close(c.path, "group 'parameters'");

  H5Handle summary = make_group(root, "summary", c);
  for (int m = 0; m < kBatchMetricCount; ++m) {
    const std::string name = kBatchMetricNames[m];
    write_vector(summary.get(), name, r.metrics.data() + static_cast<std::size_t>(m) * nv, nv, metric_units(name), c,
                 "dataset 'summary/" + name + "'");
  }
  summary.close(c.path, "group 'summary'");

  H5Handle channels = make_group(root, "channels", c);
  for (std::size_t i = 0; i < o.channels.size(); ++i) {
    const std::string name = kBatchChannelNames[o.channels[i]];
    write_transposed(channels.get(), name, r.channels.data() + i * ns * nv, ns, nv, channel_units(name), c,
                     "dataset 'channels/" + name + "'");
  }
  channels.close(c.path, "group 'channels'");

  write_transposed(root, "final_state", r.final_state.data(), static_cast<std::size_t>(r.states), nv, "", c,
                   "dataset 'final_state'");

  check_rc(H5Fflush(root, H5F_SCOPE_GLOBAL), c.path, "flushing '" + tmp + "'");
  file.close(c.path, "'" + tmp + "'");
  dcpl.close(c.path, "a property list");
  gcpl.close(c.path, "a property list");
  fcpl.close(c.path, "a property list");
}

}  // namespace

void write_batch_h5(const std::string& path, const BatchResult& r, const BatchOptions& o, const VaryDraws* draws,
                    const BatchH5Info& info) {
  check_inputs(path, r, o, draws);
  const std::string tmp = temporary_path_for(path);
  QuietHdf5Errors quiet;
  Ctx c;
  c.path = path;
  try {
    write_file(tmp, r, o, draws, info, c);  // every HDF5 handle is closed when this returns or throws
    commit_file(tmp, path);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw;
  }
}

}  // namespace terracal::rom
