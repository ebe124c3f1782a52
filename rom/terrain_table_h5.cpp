#include "rom/terrain_table_h5.hpp"

#include <hdf5.h>
#include <hdf5_hl.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <mutex>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "core/hdf5_util.hpp"
#include "core/quiet_hdf5_errors.hpp"
#include "rom/rom_vehicle.hpp"

namespace terracal::rom {

namespace {

constexpr const char* kFormat = "terracal wheel table 1";

void check_axis(const std::string& where, const std::vector<double>& x, double lo, double hi, bool strict_lo) {
  if (x.empty()) throw InputError(fmt::format("{}: empty", where));
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i]) || x[i] > hi || (strict_lo ? x[i] <= lo : x[i] < lo))
      throw InputError(fmt::format("{}: entry {} = {} is outside {}{}, {}]", where, i, x[i], strict_lo ? "(" : "[", lo, hi));
    if (i > 0 && !(x[i] > x[i - 1]))
      throw InputError(fmt::format("{}: entries must increase; entry {} = {} follows {}", where, i, x[i], x[i - 1]));
  }
}

// The checks every table passes, written or read.
void validate(const TerrainTable& t, const std::string& where) {
  check_axis(where + ": load_N", t.load, 0, 1e7, true);
  check_axis(where + ": slip", t.slip, -1, 1, false);
  check_axis(where + ": slip_angle_rad", t.angle, 0, 0.7853981633974483, false);
  if (t.slip.back() <= 0)
    throw InputError(fmt::format("{}: slip: needs a slip above zero (largest {})", where, t.slip.back()));
  if (std::find(t.slip.begin(), t.slip.end(), 0.0) == t.slip.end())
    throw InputError(fmt::format("{}: slip: needs slip 0 (the thrust and resistance of a wheel rolling without slip)",
                                 where));
  if (t.angle.size() > 1 && t.angle[0] != 0)
    throw InputError(fmt::format("{}: slip_angle_rad: with several slip angles the first must be 0 (got {})", where,
                                 t.angle[0]));
  if (!(t.radius > 0 && t.radius <= 10) || !(t.width > 0 && t.width <= 10))
    throw InputError(fmt::format("{}: wheel_radius_m {} and wheel_width_m {} must lie in (0, 10]", where, t.radius,
                                 t.width));
  const std::size_t n = t.load.size() * t.slip.size() * t.angle.size();
  const std::pair<const char*, const std::vector<double>*> arrays[] = {
      {"dbp_N", &t.dbp}, {"torque_Nm", &t.torque}, {"sinkage_m", &t.sinkage}, {"lateral_N", &t.lateral}};
  for (const auto& [name, a] : arrays) {
    if (a->size() != n)
      throw InputError(fmt::format("{}: {}: {} values, expected load x slip x slip angle = {}", where, name, a->size(), n));
    for (std::size_t i = 0; i < n; ++i)
      if (!std::isfinite((*a)[i])) throw InputError(fmt::format("{}: {}: entry {} is not finite", where, name, i));
  }
}

}  // namespace

TerrainTableView TerrainTable::view() const {
  TerrainTableView v;
  v.n_load = int(load.size());
  v.n_slip = int(slip.size());
  v.n_angle = int(angle.size());
  v.load = load.data();
  v.slip = slip.data();
  v.angle = angle.data();
  v.thrust = thrust.data();
  v.resistance = resistance.data();
  v.lateral = lateral_coef.data();
  v.radius = radius;
  return v;
}

void finish_coefficients(TerrainTable& t) {
  const std::size_t n = t.dbp.size();
  t.thrust.resize(n);
  t.resistance.resize(n);
  t.lateral_coef.resize(n);
  for (std::size_t l = 0; l < t.load.size(); ++l)
    for (std::size_t s = 0; s < t.slip.size(); ++s)
      for (std::size_t a = 0; a < t.angle.size(); ++a) {
        const std::size_t i = t.index(l, s, a);
        const double fz = t.load[l], h = t.torque[i] / t.radius;
        t.thrust[i] = h / fz;
        t.resistance[i] = (h - t.dbp[i]) / fz;
        t.lateral_coef[i] = t.lateral[i] / fz;
      }
}

void write_terrain_table(const std::string& path, const TerrainTable& t) {
  validate(t, "wheel table '" + path + "'");
  const H5File f{"wheel table", path};
  write_hdf5_atomically(f, [&](const std::string& tmp) {
    H5Handle fcpl = timeless_plist(H5P_FILE_CREATE, f);
    H5Handle file(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, fcpl.get(), H5P_DEFAULT), H5Fclose, f,
                  "cannot create temporary file '" + tmp + "'");
    const hid_t root = file.get();
    write_text_attribute(root, "format", kFormat, f);
    write_text_attribute(root, "soil", t.soil, f);
    write_text_attribute(root, "wheel", t.wheel, f);
    for (const auto& [name, value] : {std::pair<const char*, double>{"wheel_radius_m", t.radius},
                                      {"wheel_width_m", t.width}, {"duration_s", t.duration}})
      write_number_attribute(root, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value, f);
    auto vec = [&](const char* name, const std::vector<double>& x) {
      const hsize_t d = x.size();
      check_rc(H5LTmake_dataset_double(root, name, 1, &d, x.data()), f, std::string("writing ") + name);
    };
    vec("load_N", t.load);
    vec("slip", t.slip);
    vec("slip_angle_rad", t.angle);
    const hsize_t dims[3] = {t.load.size(), t.slip.size(), t.angle.size()};
    for (const auto& [name, a] : {std::pair<const char*, const std::vector<double>*>{"dbp_N", &t.dbp},
                                  {"torque_Nm", &t.torque}, {"sinkage_m", &t.sinkage}, {"lateral_N", &t.lateral}})
      check_rc(H5LTmake_dataset_double(root, name, 3, dims, a->data()), f, std::string("writing ") + name);
    file.close(f, "the file");
  });
}

namespace {

std::vector<double> read_array(hid_t root, const std::string& path, const char* name, int rank) {
  if (H5LTfind_dataset(root, name) <= 0)
    throw InputError(fmt::format("wheel table '{}': no dataset '{}' (is it a file of terracal wheel-table?)", path, name));
  int r = 0;
  if (H5LTget_dataset_ndims(root, name, &r) < 0 || r != rank)
    throw InputError(fmt::format("wheel table '{}': dataset '{}' has rank {}, expected {}", path, name, r, rank));
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  H5T_class_t cls;
  std::size_t size = 0;
  if (H5LTget_dataset_info(root, name, dims.data(), &cls, &size) < 0 || cls != H5T_FLOAT)
    throw InputError(fmt::format("wheel table '{}': dataset '{}' must hold floating-point numbers", path, name));
  std::size_t n = 1;
  for (hsize_t d : dims) n *= static_cast<std::size_t>(d);
  std::vector<double> v(n);
  if (n > 0 && H5LTread_dataset_double(root, name, v.data()) < 0)
    throw InputError(fmt::format("wheel table '{}': cannot read dataset '{}'", path, name));
  return v;
}

double read_number(hid_t root, const std::string& path, const char* name) {
  double v = 0;
  if (H5Aexists(root, name) <= 0 || H5LTget_attribute_double(root, ".", name, &v) < 0)
    throw InputError(fmt::format("wheel table '{}': no number attribute '{}'", path, name));
  return v;
}

std::string read_text(hid_t root, const char* name) {
  if (H5Aexists(root, name) <= 0) return "";
  hsize_t dims = 0;
  H5T_class_t cls;
  std::size_t size = 0;
  if (H5LTget_attribute_info(root, ".", name, &dims, &cls, &size) < 0 || cls != H5T_STRING) return "";
  std::string s(size + 1, '\0');
  if (H5LTget_attribute_string(root, ".", name, s.data()) < 0) return "";
  s.resize(std::strlen(s.c_str()));
  return s;
}

}  // namespace

TerrainTable read_terrain_table(const std::string& path) {
  QuietHdf5Errors quiet;
  const hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (id < 0) throw InputError(fmt::format("wheel table '{}': cannot open it as an HDF5 file", path));
  struct Closer {
    hid_t id;
    ~Closer() { H5Fclose(id); }
  } closer{id};
  if (read_text(id, "format") != kFormat)
    throw InputError(fmt::format("wheel table '{}': attribute 'format' is '{}', expected '{}'", path,
                                 read_text(id, "format"), kFormat));
  TerrainTable t;
  t.load = read_array(id, path, "load_N", 1);
  t.slip = read_array(id, path, "slip", 1);
  t.angle = read_array(id, path, "slip_angle_rad", 1);
  t.dbp = read_array(id, path, "dbp_N", 3);
  t.torque = read_array(id, path, "torque_Nm", 3);
  t.sinkage = read_array(id, path, "sinkage_m", 3);
  t.lateral = read_array(id, path, "lateral_N", 3);
  t.radius = read_number(id, path, "wheel_radius_m");
  t.width = read_number(id, path, "wheel_width_m");
  t.duration = read_number(id, path, "duration_s");
  t.soil = read_text(id, "soil");
  t.wheel = read_text(id, "wheel");
  validate(t, "wheel table '" + path + "'");
  finish_coefficients(t);
  return t;
}

const TerrainTable& load_terrain_table(const std::string& path) {
  static std::mutex mutex;
  static std::map<std::string, std::unique_ptr<TerrainTable>> tables;
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = tables[path];
  if (!slot) slot = std::make_unique<TerrainTable>(read_terrain_table(path));
  return *slot;
}

void attach_terrain_table(RomVehicle& v, const std::string& path) {
  v.terrain = load_terrain_table(path).view();
  v.effects |= kEffectDeformableTerrain;
}

}  // namespace terracal::rom
