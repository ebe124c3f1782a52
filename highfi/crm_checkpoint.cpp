#include "highfi/crm_checkpoint.hpp"

#include <hdf5.h>
#include <hdf5_hl.h>

#include <cstdint>

#include <fmt/format.h>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"

namespace terracal {
namespace {

struct H5File {
  hid_t id;
  ~H5File() { if (id >= 0) H5Fclose(id); }
};

void put(hid_t f, const char* name, const std::vector<Vec4<double>>& v, const std::filesystem::path& file) {
  const hsize_t dims[2] = {hsize_t(v.size()), 4};
  if (H5LTmake_dataset_double(f, name, 2, dims, reinterpret_cast<const double*>(v.data())) < 0)
    throw RunError(fmt::format("writing '{}' to checkpoint {} failed", name, file.string()));
}

void get(hid_t f, const char* name, std::vector<Vec4<double>>& v, std::size_t n, const std::filesystem::path& file) {
  v.resize(n);
  if (n == 0) return;
  if (H5LTread_dataset_double(f, name, reinterpret_cast<double*>(v.data())) < 0)
    throw InputError(fmt::format("checkpoint {}: cannot read dataset '{}'", file.string(), name));
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
    if (!c.soil.hg.empty()) put(f.id, "soil_hg", c.soil.hg, file);  // hourglass_stiffness only
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
  }
  commit_file(tmp, file);
}

CrmCheckpoint read_crm_checkpoint(const std::filesystem::path& file) {
  if (!std::filesystem::exists(file)) throw InputError(fmt::format("checkpoint {} does not exist", file.string()));
  H5File f{H5Fopen(file.string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT)};
  if (f.id < 0) throw InputError(fmt::format("checkpoint {} is not an HDF5 file", file.string()));
  CrmCheckpoint c;
  double t = 0, steps = 0, count = 0;
  if (H5LTget_attribute_double(f.id, "/", "time", &t) < 0 || H5LTget_attribute_double(f.id, "/", "steps", &steps) < 0 ||
      H5LTget_attribute_double(f.id, "/", "particles", &count) < 0)
    throw InputError(fmt::format("checkpoint {}: missing time/steps/particles attributes", file.string()));
  c.time = t;
  c.steps = long(steps);
  char fp[64] = {0};
  H5LTget_attribute_string(f.id, "/", "fingerprint", fp);
  c.fingerprint = fp;
  const std::size_t n = std::size_t(count);
  get(f.id, "soil_pos", c.soil.pos, n, file);
  get(f.id, "soil_vel", c.soil.vel, n, file);
  get(f.id, "soil_s0", c.soil.s0, n, file);
  get(f.id, "soil_s1", c.soil.s1, n, file);
  if (H5LTfind_dataset(f.id, "soil_hg") == 1) get(f.id, "soil_hg", c.soil.hg, n, file);
  c.soil.ids.resize(n);
  if (n) H5LTread_dataset_int(f.id, "soil_ids", c.soil.ids.data());
  hsize_t dims[2] = {0, 0};
  H5T_class_t cls;
  size_t sz;
  if (H5LTget_dataset_info(f.id, "bodies", dims, &cls, &sz) >= 0 && dims[0] > 0) {
    std::vector<double> b(dims[0] * 13);
    H5LTread_dataset_double(f.id, "bodies", b.data());
    for (hsize_t i = 0; i < dims[0]; ++i) {
      const double* p = b.data() + 13 * i;
      c.bodies.push_back({{p[0], p[1], p[2]}, {p[3], p[4], p[5], p[6]}, {p[7], p[8], p[9]}, {p[10], p[11], p[12]}});
    }
  }
  return c;
}

std::string crm_fingerprint(const CrmScene& sc, CrmDevice device, bool include_bodies) {
  std::string d = fmt::format(
      "{} {} {} {} {} {} {} {} {} {} {} | {} {} {} {} {} {} | {} {} {} {} {} {} {} {} | {}{}{}{} | {} {} {}",
      sc.soil.density, sc.soil.young_modulus, sc.soil.poisson_ratio, sc.soil.mu_s, sc.soil.mu_2, sc.soil.I0,
      sc.soil.grain_diameter, sc.soil.cohesion, sc.soil.gravity.x, sc.soil.gravity.y, sc.soil.gravity.z, sc.bin.size.x,
      sc.bin.size.y, sc.bin.size.z, sc.bin.fill_height, sc.bin.fill_length, sc.bin.boundary_layers, sc.numerics.spacing,
      sc.numerics.h_over_d0, int(sc.numerics.kernel), sc.numerics.time_step, sc.numerics.viscosity_alpha,
      sc.numerics.xsph, sc.numerics.free_surface_support, int(sc.numerics.cpu_precision), sc.effects.cohesion,
      sc.effects.artificial_viscosity, sc.effects.shifting, sc.effects.active_domain, int(device), sc.settle_time, sc.settle_jitter);
  // Appended only when on, so that the keys of runs without it (caches, checkpoints) stay as they were.
  if (sc.effects.hourglass_damping) d += fmt::format(" | hourglass {}", sc.numerics.hourglass_alpha);
  if (sc.settle_jitter > 0 && sc.settle_seed != kDefaultSettleSeed) d += fmt::format(" | settle seed {}", sc.settle_seed);
  if (sc.effects.hourglass_stiffness) d += fmt::format(" | hourglass stiffness {}", sc.numerics.hourglass_beta);
  if (sc.numerics.marker_velocity != MarkerVelocity::kMirror)
    d += fmt::format(" | marker velocity {}", marker_velocity_name(sc.numerics.marker_velocity));
  if (include_bodies)
    for (const auto& b : sc.bodies) {
      d += fmt::format("|{} {} {} {} {} {} {}", b.name, int(b.shape.type), b.position.x, b.position.y, b.position.z,
                       b.motion.linear_velocity.z, b.mass);
      if (b.load_ramp > 0) d += fmt::format(" ramp {}", b.load_ramp);
      for (const auto& g : b.motion.schedule)
        d += fmt::format(" {} {} {} {} {} {} {}", g.duration, g.linear_velocity.x, g.linear_velocity.y,
                         g.linear_velocity.z, g.angular_velocity.x, g.angular_velocity.y, g.angular_velocity.z);
    }
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char ch : d) {
    h ^= ch;
    h *= 1099511628211ull;
  }
  return fmt::format("{:016x}", h);
}

}  // namespace terracal
