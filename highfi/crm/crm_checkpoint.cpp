#include "highfi/crm/crm_checkpoint.hpp"

#include <hdf5.h>
#include <hdf5_hl.h>

#include <cmath>
#include <cstdint>

#include <fmt/format.h>

#include "core/atomic_file.hpp"
#include "core/checksum.hpp"
#include "core/errors.hpp"
#include "core/quiet_hdf5_errors.hpp"

namespace terracal {
namespace {

struct H5File {
  hid_t id;
  ~H5File() {
    if (id >= 0) H5Fclose(id);
  }
};

void put(hid_t f, const char* name, const std::vector<Vec4<double>>& v, const std::filesystem::path& file) {
  const hsize_t dims[2] = {hsize_t(v.size()), 4};
  if (H5LTmake_dataset_double(f, name, 2, dims, reinterpret_cast<const double*>(v.data())) < 0)
    throw RunError(fmt::format("writing '{}' to checkpoint {} failed", name, file.string()));
}

// A string attribute of the root group, or InputError naming it.
std::string string_attribute(hid_t f, const char* name, const std::filesystem::path& file) {
  hsize_t dims = 0;
  H5T_class_t cls;
  size_t size = 0;
  if (H5LTget_attribute_info(f, "/", name, &dims, &cls, &size) < 0 || cls != H5T_STRING || size > 4096)
    throw InputError(
        fmt::format("checkpoint {}: attribute '{}' is missing or not a short string", file.string(), name));
  std::string text(size + 1, '\0');
  if (H5LTget_attribute_string(f, "/", name, text.data()) < 0)
    throw InputError(fmt::format("checkpoint {}: cannot read attribute '{}'", file.string(), name));
  return text.c_str();
}

// The rows of a dataset of shape (rows, cols); InputError unless it exists with exactly that shape
// (a corrupt particle count must not make a read run past the buffer).
void require_shape(hid_t f, const char* name, hsize_t rows, hsize_t cols, const std::filesystem::path& file) {
  hsize_t dims[2] = {0, 0};
  H5T_class_t cls;
  size_t size = 0;
  int rank = 0;
  if (H5LTget_dataset_ndims(f, name, &rank) < 0 || rank != (cols > 0 ? 2 : 1) ||
      H5LTget_dataset_info(f, name, dims, &cls, &size) < 0 || dims[0] != rows || (cols > 0 && dims[1] != cols))
    throw InputError(
        fmt::format("checkpoint {}: dataset '{}' is missing or not of {} rows", file.string(), name, rows));
}

void get(hid_t f, const char* name, std::vector<Vec4<double>>& v, std::size_t n, const std::filesystem::path& file) {
  require_shape(f, name, n, 4, file);
  v.resize(n);
  if (n == 0) return;
  if (H5LTread_dataset_double(f, name, reinterpret_cast<double*>(v.data())) < 0)
    throw InputError(fmt::format("checkpoint {}: cannot read dataset '{}'", file.string(), name));
}

// Calls f(name, slot) for every effect that keeps a record per particle: its dataset's name and slot.
template <class F>
void for_each_record_kind(F&& f) {
  for_each_effect(CrmEffects{}, [&](auto tag) {
    using E = typename decltype(tag)::type;
    if constexpr (E::kRecord) f(std::string("soil_") + E::kRecordName, kRecordSlot<E>);
  });
}

// Raised whenever the datasets or attributes change meaning; a checkpoint of another version is
// refused (a cached bed is then settled again, a run starts over).
constexpr int kCrmCheckpointVersion = 2;

// FNV-1a over everything a checkpoint restores, computed from the in-memory state: the writer
// stores it, the reader recomputes it from what it read, so a changed byte in any dataset or
// attribute shows as a mismatch.
std::string state_checksum(const CrmCheckpoint& c) {
  Fnv1a64 h;
  auto add_rows = [&](const std::vector<Vec4<double>>& v) {
    for (const auto& r : v) {
      const double x[4] = {r.x, r.y, r.z, r.w};
      h.add(x, sizeof x);
    }
  };
  add_rows(c.soil.pos);
  add_rows(c.soil.vel);
  add_rows(c.soil.s0);
  add_rows(c.soil.s1);
  for (const auto& r : c.soil.records) add_rows(r);
  h.add(c.soil.ids.data(), c.soil.ids.size() * sizeof(int));
  for (const BodyState& s : c.bodies)
    for (double x : {s.position.x, s.position.y, s.position.z, s.orientation.w, s.orientation.x, s.orientation.y,
                     s.orientation.z, s.velocity.x, s.velocity.y, s.velocity.z, s.omega.x, s.omega.y, s.omega.z})
      h.add(&x, sizeof x);
  h.add(fmt::format("|{:.17g}|{}|{}", c.time, c.steps, c.fingerprint));
  return h.hex();
}

}  // namespace

void write_crm_checkpoint(const std::filesystem::path& file, const CrmCheckpoint& c) {
  const std::filesystem::path tmp = temporary_path_for(file);
  {
    H5File f{H5Fcreate(tmp.string().c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT)};
    if (f.id < 0) throw RunError(fmt::format("cannot create checkpoint {}", tmp.string()));
    put(f.id, "soil_pos", c.soil.pos, file);
    put(f.id, "soil_vel", c.soil.vel, file);
    put(f.id, "soil_s0", c.soil.s0, file);
    put(f.id, "soil_s1", c.soil.s1, file);
    for_each_record_kind([&](const std::string& name, int slot) {  // the named effects' records only
      if (!c.soil.records[slot].empty()) put(f.id, name.c_str(), c.soil.records[slot], file);
    });
    const hsize_t n[1] = {hsize_t(c.soil.ids.size())};
    H5LTmake_dataset_int(f.id, "soil_ids", 1, n, c.soil.ids.data());
    std::vector<double> b;
    for (const BodyState& s : c.bodies)
      for (double x : {s.position.x, s.position.y, s.position.z, s.orientation.w, s.orientation.x, s.orientation.y,
                       s.orientation.z, s.velocity.x, s.velocity.y, s.velocity.z, s.omega.x, s.omega.y, s.omega.z})
        b.push_back(x);
    const hsize_t bd[2] = {hsize_t(c.bodies.size()), 13};
    H5LTmake_dataset_double(f.id, "bodies", 2, bd, b.data());
    const double t = c.time, steps = double(c.steps), count = double(c.soil.size());
    H5LTset_attribute_double(f.id, "/", "time", &t, 1);
    H5LTset_attribute_double(f.id, "/", "steps", &steps, 1);
    H5LTset_attribute_double(f.id, "/", "particles", &count, 1);
    H5LTset_attribute_string(f.id, "/", "fingerprint", c.fingerprint.c_str());
    const int version = kCrmCheckpointVersion;
    H5LTset_attribute_int(f.id, "/", "format_version", &version, 1);
    H5LTset_attribute_string(f.id, "/", "checksum", state_checksum(c).c_str());
  }
  commit_file(tmp, file);
}

CrmCheckpoint read_crm_checkpoint(const std::filesystem::path& file) {
  if (!std::filesystem::exists(file)) throw InputError(fmt::format("checkpoint {} does not exist", file.string()));
  const QuietHdf5Errors quiet;
  H5File f{H5Fopen(file.string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT)};
  if (f.id < 0) throw InputError(fmt::format("checkpoint {} is not an HDF5 file", file.string()));
  int version = 0;
  if (H5LTget_attribute_int(f.id, "/", "format_version", &version) < 0 || version != kCrmCheckpointVersion)
    throw InputError(fmt::format("checkpoint {}: format version {}, this terracal reads version {}", file.string(),
                                 version, kCrmCheckpointVersion));
  CrmCheckpoint c;
  double t = 0, steps = 0, count = 0;
  if (H5LTget_attribute_double(f.id, "/", "time", &t) < 0 || H5LTget_attribute_double(f.id, "/", "steps", &steps) < 0 ||
      H5LTget_attribute_double(f.id, "/", "particles", &count) < 0)
    throw InputError(fmt::format("checkpoint {}: missing time/steps/particles attributes", file.string()));
  c.time = t;
  c.steps = long(steps);
  c.fingerprint = string_attribute(f.id, "fingerprint", file);
  if (!(count >= 0 && count < 1e12 && count == std::floor(count)))
    throw InputError(fmt::format("checkpoint {}: particle count {} is not a count", file.string(), count));
  const std::size_t n = std::size_t(count);
  get(f.id, "soil_pos", c.soil.pos, n, file);
  get(f.id, "soil_vel", c.soil.vel, n, file);
  get(f.id, "soil_s0", c.soil.s0, n, file);
  get(f.id, "soil_s1", c.soil.s1, n, file);
  for_each_record_kind([&](const std::string& name, int slot) {
    if (H5LTfind_dataset(f.id, name.c_str()) == 1) get(f.id, name.c_str(), c.soil.records[slot], n, file);
  });
  require_shape(f.id, "soil_ids", n, 0, file);
  c.soil.ids.resize(n);
  if (n && H5LTread_dataset_int(f.id, "soil_ids", c.soil.ids.data()) < 0)
    throw InputError(fmt::format("checkpoint {}: cannot read dataset 'soil_ids'", file.string()));
  hsize_t dims[2] = {0, 0};
  H5T_class_t cls;
  size_t sz;
  int rank = 0;
  // No 'bodies' dataset reads as no bodies; the checksum tells whether there should have been some.
  const bool has_bodies = H5LTfind_dataset(f.id, "bodies") == 1;
  if (has_bodies && (H5LTget_dataset_ndims(f.id, "bodies", &rank) < 0 || rank != 2))
    throw InputError(fmt::format("checkpoint {}: dataset 'bodies' is missing or not a table", file.string()));
  if (has_bodies && H5LTget_dataset_info(f.id, "bodies", dims, &cls, &sz) >= 0 && dims[0] > 0) {
    std::vector<double> b(dims[0] * 13);
    if (dims[1] != 13 || H5LTread_dataset_double(f.id, "bodies", b.data()) < 0)
      throw InputError(fmt::format("checkpoint {}: cannot read dataset 'bodies'", file.string()));
    for (hsize_t i = 0; i < dims[0]; ++i) {
      const double* p = b.data() + 13 * i;
      c.bodies.push_back({{p[0], p[1], p[2]}, {p[3], p[4], p[5], p[6]}, {p[7], p[8], p[9]}, {p[10], p[11], p[12]}});
    }
  }
  if (string_attribute(f.id, "checksum", file) != state_checksum(c))
    throw InputError(
        fmt::format("checkpoint {}: checksum mismatch: the file changed after it was written", file.string()));
  return c;
}

std::string crm_fingerprint(const CrmScene& sc, CrmDevice device, bool include_bodies) {
  const CrmSoil& soil = sc.soil;
  const CrmBin& bin = sc.bin;
  const CrmNumerics& n = sc.numerics;
  std::string d =
      fmt::format("soil {} {} {} {} {} {} {} {} {} {} {} | bin {} {} {} {} {} {}", soil.density, soil.young_modulus,
                  soil.poisson_ratio, soil.mu_s, soil.mu_2, soil.I0, soil.grain_diameter, soil.cohesion, soil.gravity.x,
                  soil.gravity.y, soil.gravity.z, bin.size.x, bin.size.y, bin.size.z, bin.fill_height, bin.fill_length,
                  bin.boundary_layers);
  d += fmt::format(" | resolution {} {} {} {} {} {} {} {} wall_contact {} skin {} | device {} | settle {} {}", n.spacing,
                   n.h_over_d0, int(n.kernel), n.time_step, n.free_surface_support, int(n.cpu_precision),
                   marker_velocity_name(n.marker_velocity), n.grid_reach, n.wall_contact, n.sort_skin, int(device),
                   sc.settle_time, sc.settle_jitter);
  if (sc.settle_jitter > 0) d += fmt::format(" seed {}", sc.settle_seed);
  d += " | effects " + effects_text(sc.effects);
  if (include_bodies)
    for (const auto& b : sc.bodies) {
      d += fmt::format("|{} {} {} {} {} {} {}", b.name, int(b.shape.type), b.position.x, b.position.y, b.position.z,
                       b.motion.linear_velocity.z, b.mass);
      if (b.load_ramp > 0) d += fmt::format(" ramp {}", b.load_ramp);
      for (const auto& g : b.motion.schedule)
        d += fmt::format(" {} {} {} {} {} {} {}", g.duration, g.linear_velocity.x, g.linear_velocity.y,
                         g.linear_velocity.z, g.angular_velocity.x, g.angular_velocity.y, g.angular_velocity.z);
    }
  return fnv1a64_hex(d);
}

}  // namespace terracal
