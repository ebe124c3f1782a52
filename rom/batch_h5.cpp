#include "rom/batch_h5.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/hdf5_util.hpp"

namespace terracal::rom {
namespace {

struct Ctx {
  H5File file;
  hid_t gcpl = H5I_INVALID_HID;
  hid_t dcpl = H5I_INVALID_HID;
};

void double_attribute(hid_t loc, const std::string& name, double v, const Ctx& c) {
  write_number_attribute(loc, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &v, c.file);
}

H5Handle make_dataset(hid_t loc, const std::string& name, const std::vector<hsize_t>& extent, const Ctx& c,
                      const std::string& what) {
  return create_dataset(loc, name, H5T_IEEE_F64LE, extent, c.dcpl, c.file, what);
}

// A 1-D float64 dataset of n values (units: attribute "units" unless empty).
void write_vector(hid_t loc, const std::string& name, const double* data, std::size_t n, const std::string& units,
                  const Ctx& c, const std::string& what) {
  H5Handle ds = make_dataset(loc, name, {static_cast<hsize_t>(n)}, c, what);
  if (n > 0)
    check_rc(H5Dwrite(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), c.file, "writing " + what);
  if (!units.empty()) write_text_attribute(ds.get(), "units", units, c.file);
  ds.close(c.file, what);
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
    H5Handle file_space(H5Dget_space(ds.get()), H5Sclose, c.file, "reading the dataspace of " + what);
    for (std::size_t v0 = 0; v0 < nv; v0 += block) {
      const std::size_t nb = std::min(block, nv - v0);
      for (std::size_t a = 0; a < na; ++a) {
        const double* row = src + a * nv + v0;
        for (std::size_t v = 0; v < nb; ++v) buffer[v * na + a] = row[v];
      }
      const hsize_t start[2] = {static_cast<hsize_t>(v0), 0};
      const hsize_t count[2] = {static_cast<hsize_t>(nb), static_cast<hsize_t>(na)};
      check_rc(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start, nullptr, count, nullptr), c.file,
               "selecting rows of " + what);
      H5Handle mem_space(H5Screate_simple(2, count, nullptr), H5Sclose, c.file, "creating a memory dataspace");
      check_rc(H5Dwrite(ds.get(), H5T_NATIVE_DOUBLE, mem_space.get(), file_space.get(), H5P_DEFAULT, buffer.data()),
               c.file, "writing " + what);
      mem_space.close(c.file, "a dataspace");
    }
    file_space.close(c.file, "a dataspace");
  }
  if (!units.empty()) write_text_attribute(ds.get(), "units", units, c.file);
  ds.close(c.file, what);
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

// Everything that can be wrong with the inputs is found before the file is created.
void check_inputs(const H5File& file, const BatchResult& r, const BatchOptions& o, const VaryDraws* draws) {
  if (r.vehicles < 0 || r.samples < 0 || r.states < 0)
    refuse(file, "negative count (vehicles " + std::to_string(r.vehicles) + ", samples " + std::to_string(r.samples) +
                     ", states " + std::to_string(r.states) + ")");
  const std::size_t nv = static_cast<std::size_t>(r.vehicles), ns = static_cast<std::size_t>(r.samples);
  auto sized = [&](const std::vector<double>& v, std::size_t want, const std::string& what) {
    if (v.size() != want)
      refuse(file, what + " holds " + std::to_string(v.size()) + " values, expected " + std::to_string(want));
  };
  sized(r.metrics, static_cast<std::size_t>(kBatchMetricCount) * nv, "the summary metrics");
  sized(r.channels, o.channels.size() * ns * nv, "the channels");
  sized(r.final_state, static_cast<std::size_t>(r.states) * nv, "the final state");
  for (std::size_t i = 0; i < o.channels.size(); ++i) {
    if (o.channels[i] < 0 || o.channels[i] >= kBatchChannelCount)
      refuse(file, "channel number " + std::to_string(static_cast<int>(o.channels[i])) + " is unknown");
    for (std::size_t j = 0; j < i; ++j)
      if (o.channels[j] == o.channels[i])
        refuse(file, std::string("channel '") + kBatchChannelNames[o.channels[i]] + "' is listed twice");
  }
  if (ns > 0 && !(o.output_rate > 0))
    refuse(file, "samples without a positive output rate (" + std::to_string(o.output_rate) + ")");
  if (!draws) return;
  if (draws->values.size() != draws->names.size())
    refuse(file, "the draws have " + std::to_string(draws->names.size()) + " names but " +
                     std::to_string(draws->values.size()) + " value lists");
  for (std::size_t p = 0; p < draws->names.size(); ++p) {
    check_object_name(draws->names[p], file, "parameter");
    for (std::size_t q = 0; q < p; ++q)
      if (draws->names[q] == draws->names[p]) refuse(file, "parameter '" + draws->names[p] + "' appears twice");
    if (draws->values[p].size() != nv)
      refuse(file, "parameter '" + draws->names[p] + "' has " + std::to_string(draws->values[p].size()) +
                       " values for " + std::to_string(nv) + " vehicles");
  }
}

void write_file(const std::string& tmp, const BatchResult& r, const BatchOptions& o, const VaryDraws* draws,
                const BatchH5Info& info, Ctx& c) {
  H5Handle fcpl = timeless_plist(H5P_FILE_CREATE, c.file);
  H5Handle gcpl = timeless_plist(H5P_GROUP_CREATE, c.file);
  H5Handle dcpl = timeless_plist(H5P_DATASET_CREATE, c.file);
  c.gcpl = gcpl.get();
  c.dcpl = dcpl.get();
  H5Handle file(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, fcpl.get(), H5P_DEFAULT), H5Fclose, c.file,
                "cannot create temporary file '" + tmp + "'");
  const hid_t root = file.get();
  const std::size_t nv = static_cast<std::size_t>(r.vehicles), ns = static_cast<std::size_t>(r.samples);

  write_text_attribute(root, "model", info.model.empty() ? std::string(model_name(o.model)) : info.model, c.file);
  write_text_attribute(root, "vehicle", info.vehicle, c.file);
  double_attribute(root, "step", o.step, c);
  double_attribute(root, "end_time", o.end_time, c);
  double_attribute(root, "initial_speed", o.initial_speed, c);
  double_attribute(root, "output_rate", o.output_rate, c);
  const std::int64_t vehicles = r.vehicles, failed = r.failed;
  write_number_attribute(root, "vehicles", H5T_STD_I64LE, H5T_NATIVE_INT64, &vehicles, c.file);
  write_number_attribute(root, "failed", H5T_STD_I64LE, H5T_NATIVE_INT64, &failed, c.file);
  const std::uint64_t seed = info.seed;
  write_number_attribute(root, "seed", H5T_STD_U64LE, H5T_NATIVE_UINT64, &seed, c.file);
  write_text_attribute(root, "device", r.device, c.file);

  std::vector<double> time(ns);
  for (std::size_t k = 0; k < ns; ++k) time[k] = static_cast<double>(k) / o.output_rate;
  write_vector(root, "time", time.data(), ns, "s", c, "dataset 'time'");

  H5Handle params = create_group(root, "parameters", c.gcpl, c.file);
  if (draws) {
    for (std::size_t p = 0; p < draws->names.size(); ++p) {
      const std::string& name = draws->names[p];
      const std::string what = "dataset 'parameters/" + name + "'";
      H5Handle ds = make_dataset(params.get(), name, {static_cast<hsize_t>(nv)}, c, what);
      if (nv > 0)
        check_rc(H5Dwrite(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, draws->values[p].data()), c.file,
                 "writing " + what);
      if (draws->units.size() == draws->names.size()) write_text_attribute(ds.get(), "units", draws->units[p], c.file);
      if (draws->distributions.size() == draws->names.size())
        write_text_attribute(ds.get(), "distribution", draws->distributions[p], c.file);
      ds.close(c.file, what);
    }
  }
  params.close(c.file, "group 'parameters'");

  H5Handle summary = create_group(root, "summary", c.gcpl, c.file);
  for (int m = 0; m < kBatchMetricCount; ++m) {
    const std::string name = kBatchMetricNames[m];
    write_vector(summary.get(), name, r.metrics.data() + static_cast<std::size_t>(m) * nv, nv, metric_units(name), c,
                 "dataset 'summary/" + name + "'");
  }
  summary.close(c.file, "group 'summary'");

  H5Handle channels = create_group(root, "channels", c.gcpl, c.file);
  for (std::size_t i = 0; i < o.channels.size(); ++i) {
    const std::string name = kBatchChannelNames[o.channels[i]];
    write_transposed(channels.get(), name, r.channels.data() + i * ns * nv, ns, nv, channel_units(name), c,
                     "dataset 'channels/" + name + "'");
  }
  channels.close(c.file, "group 'channels'");

  write_transposed(root, "final_state", r.final_state.data(), static_cast<std::size_t>(r.states), nv, "", c,
                   "dataset 'final_state'");

  check_rc(H5Fflush(root, H5F_SCOPE_GLOBAL), c.file, "flushing '" + tmp + "'");
  file.close(c.file, "'" + tmp + "'");
  dcpl.close(c.file, "a property list");
  gcpl.close(c.file, "a property list");
  fcpl.close(c.file, "a property list");
}

}  // namespace

void write_batch_h5(const std::string& path, const BatchResult& r, const BatchOptions& o, const VaryDraws* draws,
                    const BatchH5Info& info) {
  Ctx c;
  c.file = {"batch file", path};
  check_inputs(c.file, r, o, draws);
  write_hdf5_atomically(c.file, [&](const std::string& tmp) { write_file(tmp, r, o, draws, info, c); });
}

}  // namespace terracal::rom
