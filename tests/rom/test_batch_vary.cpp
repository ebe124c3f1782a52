// --vary distributions for vehicle batches (rom/batch_vary.hpp) and the batch.h5 writer
// (rom/batch_h5.hpp).
#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "core/errors.hpp"
#include "core/rng.hpp"
#include "rom/batch_h5.hpp"
#include "rom/batch_vary.hpp"
#include "tests/rom/rom_test_vehicles.hpp"
#include "tests/scratch_dir.hpp"

using namespace terracal;
using namespace terracal::rom;
using nlohmann::json;

namespace {

VarySpec spec(const char* text) { return vary_from_json(json::parse(text), "vary.json"); }

std::size_t index_of(const VaryDraws& d, const std::string& name) {
  const auto it = std::find(d.names.begin(), d.names.end(), name);
  REQUIRE(it != d.names.end());
  return static_cast<std::size_t>(it - d.names.begin());
}

struct Moments {
  double mean = 0, sd = 0, min = 1e300, max = -1e300;
};
Moments moments(const std::vector<double>& x) {
  Moments m;
  for (double v : x) {
    m.mean += v;
    m.min = std::min(m.min, v);
    m.max = std::max(m.max, v);
  }
  m.mean /= static_cast<double>(x.size());
  for (double v : x) m.sd += (v - m.mean) * (v - m.mean);
  m.sd = std::sqrt(m.sd / static_cast<double>(x.size() - 1));
  return m;
}

std::string thrown(const VarySpec& s, long n, std::uint64_t seed) {
  try {
    draw_vehicles(testing::hmmwv(), s, n, seed);
  } catch (const InputError& e) {
    return e.what();
  }
  FAIL("no InputError");
  return {};
}

std::string thrown(const char* text) {
  try {
    spec(text);
  } catch (const InputError& e) {
    return e.what();
  }
  FAIL("no InputError for " << text);
  return {};
}

}  // namespace

TEST_CASE("vary: 20000 normal draws have the asked mean and sd, every vehicle gets its own value", "[rom_batch_vary]") {
  const RomVehicle base = testing::hmmwv();
  const VaryDraws d =
      draw_vehicles(base, spec(R"({"mass": {"distribution": "normal", "mean": 2100, "sd": 50}})"), 20000, 42);
  REQUIRE(d.names == std::vector<std::string>{"mass"});
  REQUIRE(d.units == std::vector<std::string>{"kg"});
  REQUIRE(d.distributions == std::vector<std::string>{"normal(mean 2100, sd 50)"});
  REQUIRE(d.values.size() == 1);
  REQUIRE(d.values[0].size() == 20000);
  REQUIRE(d.vehicles.size() == 20000);
  const Moments m = moments(d.values[0]);
  INFO("mean " << m.mean << ", sd " << m.sd);
  CHECK(std::abs(m.mean - 2100) < 0.03 * 50);  // 3 % of the sd (~4 standard errors)
  CHECK(m.sd == Approx(50).epsilon(0.03));
  for (std::size_t i = 0; i < d.vehicles.size(); i += 997) {
    CHECK(d.vehicles[i].mass == d.values[0][i]);
    CHECK(d.vehicles[i].yaw_inertia == base.yaw_inertia);  // the rest is the base's
  }
}

TEST_CASE("vary: lognormal draws are positive with mean exp(mu + sigma^2 / 2), uniform ones stay in (low, high)",
          "[rom_batch_vary]") {
  const double mu = std::log(4519.0), sigma = 0.1;
  const VaryDraws d = draw_vehicles(testing::hmmwv(),
                                    spec(fmt::format(R"({{"yaw_inertia": {{"distribution": "lognormal", "mu": {},
                                                         "sigma": {}}},
                                                         "friction": {{"distribution": "uniform", "low": 0.5,
                                                         "high": 1.0}}}})",
                                                     mu, sigma)
                                             .c_str()),
                                    20000, 3);
  REQUIRE(d.names == std::vector<std::string>{"friction", "yaw_inertia"});  // sorted by name
  const Moments ln = moments(d.values[index_of(d, "yaw_inertia")]);
  CHECK(ln.min > 0);
  CHECK(ln.mean == Approx(std::exp(mu + 0.5 * sigma * sigma)).epsilon(0.01));
  Moments logs;
  {
    std::vector<double> l;
    for (double v : d.values[index_of(d, "yaw_inertia")]) l.push_back(std::log(v));
    logs = moments(l);
  }
  CHECK(logs.sd == Approx(sigma).epsilon(0.03));
  const Moments u = moments(d.values[index_of(d, "friction")]);
  CHECK(u.min > 0.5);
  CHECK(u.max < 1.0);
  CHECK(u.min < 0.501);
  CHECK(u.max > 0.999);
  CHECK(u.mean == Approx(0.75).epsilon(0.01));
  CHECK(u.sd == Approx(0.5 / std::sqrt(12.0)).epsilon(0.03));
  CHECK(d.vehicles[17].friction == d.values[index_of(d, "friction")][17]);
}

TEST_CASE("vary: one seed gives the same draws, another different ones, streams are per parameter",
          "[rom_batch_vary]") {
  const RomVehicle base = testing::hmmwv();
  const VarySpec two = spec(R"({"mass": {"distribution": "normal", "mean": 2100, "sd": 50},
                                "friction": {"distribution": "uniform", "low": 0.5, "high": 1.0}})");
  const VaryDraws a = draw_vehicles(base, two, 1000, 11), b = draw_vehicles(base, two, 1000, 11);
  const VaryDraws c = draw_vehicles(base, two, 1000, 12);
  CHECK(a.values == b.values);
  for (std::size_t i = 0; i < a.vehicles.size(); i += 101)
    CHECK(std::memcmp(&a.vehicles[i], &b.vehicles[i], sizeof(RomVehicle)) == 0);
  for (std::size_t p = 0; p < 2; ++p) {
    std::size_t same = 0;
    for (std::size_t i = 0; i < 1000; ++i) same += a.values[p][i] == c.values[p][i];
    CHECK(same == 0);
  }
  // The first m of n vehicles are those drawn with n = m, and a parameter's values do not depend on
  // what else is varied.
  const VaryDraws prefix = draw_vehicles(base, two, 10, 11);
  for (std::size_t p = 0; p < 2; ++p)
    CHECK(prefix.values[p] == std::vector<double>(a.values[p].begin(), a.values[p].begin() + 10));
  const VaryDraws mass_only =
      draw_vehicles(base, spec(R"({"mass": {"distribution": "normal", "mean": 2100, "sd": 50}})"), 1000, 11);
  CHECK(mass_only.values[0] == a.values[index_of(a, "mass")]);
  // The documented stream: Rng::for_stream(seed, catalogue index), fma(sd, normal(), mean).
  const auto& names = vary_parameter_names();
  const auto k = static_cast<std::uint64_t>(std::find(names.begin(), names.end(), "mass") - names.begin());
  Rng rng = Rng::for_stream(11, k);
  for (int i = 0; i < 5; ++i) CHECK(mass_only.values[0][i] == std::fma(50, rng.normal(), 2100));
}

TEST_CASE("vary: scales multiply the base's values, cg_to_front keeps the wheelbase", "[rom_batch_vary]") {
  const RomVehicle base = testing::hmmwv();
  const VaryDraws d = draw_vehicles(base, spec(R"({
      "cg_to_front": {"distribution": "uniform", "low": 1.5, "high": 1.9},
      "tire_cornering_scale": {"distribution": "uniform", "low": 0.9, "high": 1.1},
      "tire_longitudinal_scale": {"distribution": "lognormal", "mu": 0, "sigma": 0.05},
      "torque_scale": {"distribution": "uniform", "low": 0.8, "high": 1.2},
      "roll_stiffness_rear": {"distribution": "normal", "mean": 30000, "sd": 1000},
      "max_brake_torque": {"distribution": "uniform", "low": 3000, "high": 5000}})"),
                                    50, 5);
  for (std::size_t i = 0; i < d.vehicles.size(); ++i) {
    const RomVehicle& v = d.vehicles[i];
    const double a = d.values[index_of(d, "cg_to_front")][i];
    CHECK(v.cg_to_front == a);
    CHECK(v.wheelbase() == Approx(base.wheelbase()).epsilon(1e-14));
    const double cs = d.values[index_of(d, "tire_cornering_scale")][i];
    const double ls = d.values[index_of(d, "tire_longitudinal_scale")][i];
    for (int ax = 0; ax < 2; ++ax)
      for (int l = 0; l < 2; ++l) {
        CHECK(v.tire[ax].y[l].df0 == cs * base.tire[ax].y[l].df0);
        CHECK(v.tire[ax].x[l].df0 == ls * base.tire[ax].x[l].df0);
        CHECK(v.tire[ax].y[l].fm == base.tire[ax].y[l].fm);
      }
    const double ts = d.values[index_of(d, "torque_scale")][i];
    for (int k = 0; k < base.powertrain.max_torque.n; ++k)
      CHECK(v.powertrain.max_torque.y[k] == ts * base.powertrain.max_torque.y[k]);
    CHECK(v.powertrain.max_torque.x[3] == base.powertrain.max_torque.x[3]);
    CHECK(v.roll_stiffness[1] == d.values[index_of(d, "roll_stiffness_rear")][i]);
    CHECK(v.roll_stiffness[0] == base.roll_stiffness[0]);
    CHECK(v.powertrain.max_brake_torque == d.values[index_of(d, "max_brake_torque")][i]);
  }
  CHECK(vary_parameter_unit("roll_damping_front") == "N m s/rad");
  CHECK(vary_parameter_unit("torque_scale") == "-");
  CHECK(vary_parameter_names().size() == 22);
  // The per-axle cornering scales act on one axle; rolling_resistance sets every tire's coefficient.
  RomVehicle v = base;
  apply_vary_parameter(v, base, "tire_cornering_scale_rear", 0.7);
  apply_vary_parameter(v, base, "rolling_resistance", 0.03);
  for (int l = 0; l < 2; ++l) {
    CHECK(v.tire[0].y[l].df0 == base.tire[0].y[l].df0);
    CHECK(v.tire[1].y[l].df0 == 0.7 * base.tire[1].y[l].df0);
  }
  apply_vary_parameter(v, base, "tire_cornering_scale_front", 1.3);
  for (int l = 0; l < 2; ++l) CHECK(v.tire[0].y[l].df0 == 1.3 * base.tire[0].y[l].df0);
  CHECK(v.tire[0].rolling_resistance == 0.03);
  CHECK(v.tire[1].rolling_resistance == 0.03);
}

TEST_CASE("vary: the roll stiffness's sum and front share give one vehicle in either order", "[rom_batch_vary]") {
  RomVehicle base = testing::hmmwv();
  base.roll_stiffness[0] = 30000;
  base.roll_stiffness[1] = 50000;
  RomVehicle a = base, b = base;
  apply_vary_parameter(a, base, "roll_stiffness_total", 120000);
  apply_vary_parameter(a, base, "roll_stiffness_front_share", 0.25);
  apply_vary_parameter(b, base, "roll_stiffness_front_share", 0.25);
  apply_vary_parameter(b, base, "roll_stiffness_total", 120000);
  CHECK(a.roll_stiffness[0] == Approx(30000).epsilon(1e-14));
  CHECK(a.roll_stiffness[1] == Approx(90000).epsilon(1e-14));
  CHECK(b.roll_stiffness[0] == Approx(a.roll_stiffness[0]).epsilon(1e-14));
  CHECK(b.roll_stiffness[1] == Approx(a.roll_stiffness[1]).epsilon(1e-14));
  // Each alone keeps the other: the total keeps the base's share 3/8, the share keeps the total 80000.
  RomVehicle t = base, s = base;
  apply_vary_parameter(t, base, "roll_stiffness_total", 160000);
  CHECK(t.roll_stiffness[0] == Approx(60000).epsilon(1e-14));
  apply_vary_parameter(s, base, "roll_stiffness_front_share", 0.5);
  CHECK(s.roll_stiffness[0] == Approx(40000).epsilon(1e-14));
  CHECK(s.roll_stiffness[1] == Approx(40000).epsilon(1e-14));
  CHECK(vary_parameter_range("roll_stiffness_front_share").contains(0.5));
  CHECK_FALSE(vary_parameter_range("roll_stiffness_front_share").contains(1.0));
}

TEST_CASE("vary: parameters that set the same values are refused together", "[rom_batch_vary]") {
  using Catch::Contains;
  CHECK_THAT(thrown(R"({"roll_stiffness_total": {"distribution": "normal", "mean": 6e4, "sd": 1e3},
                       "roll_stiffness_rear": {"distribution": "normal", "mean": 3e4, "sd": 1e3}})"),
             Contains("vary.json") && Contains("'roll_stiffness_total'") && Contains("'roll_stiffness_rear'"));
  CHECK_THAT(thrown(R"({"tire_cornering_scale": {"distribution": "uniform", "low": 0.9, "high": 1.1},
                       "tire_cornering_scale_front": {"distribution": "uniform", "low": 0.9, "high": 1.1}})"),
             Contains("'tire_cornering_scale'") && Contains("'tire_cornering_scale_front'"));
  CHECK(overlapping_parameters({"roll_stiffness_total", "roll_stiffness_front_share", "mass"}).empty());
}

TEST_CASE("vary: bad files are refused naming the key and the value", "[rom_batch_vary]") {
  using Catch::Contains;
  std::string m = thrown(R"({"masss": {"distribution": "normal", "mean": 2100, "sd": 50}})");
  CHECK_THAT(m, Contains("vary.json") && Contains("'masss'") && Contains("unknown parameter") && Contains("mass, "));
  m = thrown(R"({"mass": {"distribution": "gaussian", "mean": 2100, "sd": 50}})");
  CHECK_THAT(m, Contains("'mass.distribution'") && Contains("gaussian") && Contains("lognormal"));
  m = thrown(R"({"mass": {"distribution": "normal", "mean": 2100, "sd": 0}})");
  CHECK_THAT(m, Contains("'mass.sd'") && Contains("value 0 ") && Contains("positive"));
  m = thrown(R"({"mass": {"distribution": "normal", "mean": 2100, "sd": -3}})");
  CHECK_THAT(m, Contains("'mass.sd'") && Contains("-3"));
  m = thrown(R"({"mass": {"distribution": "lognormal", "mu": 7, "sigma": 0}})");
  CHECK_THAT(m, Contains("'mass.sigma'") && Contains("value 0 "));
  m = thrown(R"({"friction": {"distribution": "uniform", "low": 1.0, "high": 0.5}})");
  CHECK_THAT(m, Contains("'friction.high'") && Contains("0.5") && Contains("low"));
  m = thrown(R"({"friction": {"distribution": "uniform", "low": 0.7, "high": 0.7}})");
  CHECK_THAT(m, Contains("'friction.high'") && Contains("0.7"));
  m = thrown(R"({"mass": {"distribution": "uniform", "low": -10, "high": 100}})");
  CHECK_THAT(m, Contains("'mass.low'") && Contains("-10"));
  m = thrown(R"({"mass": {"distribution": "uniform", "low": 1, "high": 100, "sd": 4}})");
  CHECK_THAT(m, Contains("'mass.sd'") && Contains("unknown key") && Contains("low, high"));
  m = thrown(R"({"mass": {"mean": 2100, "sd": 50}})");
  CHECK_THAT(m, Contains("'mass.distribution'") && Contains("missing"));
  m = thrown(R"({"mass": {"distribution": "normal", "sd": 50}})");
  CHECK_THAT(m, Contains("'mass.mean'") && Contains("missing"));
  m = thrown(R"({"mass": 2100})");
  CHECK_THAT(m, Contains("'mass'") && Contains("2100") && Contains("not a JSON object"));
  m = thrown(R"({})");
  CHECK_THAT(m, Contains("no parameter"));
  m = thrown(R"([1, 2])");
  CHECK_THAT(m, Contains("JSON object"));
}

TEST_CASE("vary: read_vary reads a file and names it in messages", "[rom_batch_vary]") {
  test::ScratchDir dir("batch_vary");
  const std::string good = dir.str() + "/vary.json", bad = dir.str() + "/bad.json";
  std::ofstream(good) << R"({"gravity": {"distribution": "uniform", "low": 9.7, "high": 9.9}})";
  std::ofstream(bad) << R"({"gravity": {"distribution": "uniform", "low": 9.7, "high": 9.9}, "drag": {}})";
  const VarySpec s = read_vary(good);
  REQUIRE(s.parameters.size() == 1);
  CHECK(s.parameters[0].name == "gravity");
  CHECK(s.parameters[0].distribution == VaryDistribution::kUniform);
  CHECK(s.parameters[0].a == 9.7);
  CHECK(s.parameters[0].b == 9.9);
  CHECK(s.source == good);
  CHECK_THROWS_WITH(read_vary(bad), Catch::Contains(bad) && Catch::Contains("'drag'"));
  CHECK_THROWS_AS(read_vary(dir.str() + "/none.json"), InputError);
}

TEST_CASE("vary: a draw outside the allowed values is refused with the parameter, value and vehicle",
          "[rom_batch_vary]") {
  using Catch::Contains;
  // mass ~ normal(1500, 600): about 1 draw in 160 is negative. The first one, from the documented
  // stream, is what the message names (the vehicles are built in parallel).
  const VarySpec s = spec(R"({"mass": {"distribution": "normal", "mean": 1500, "sd": 600}})");
  const auto& names = vary_parameter_names();
  Rng rng =
      Rng::for_stream(7, static_cast<std::uint64_t>(std::find(names.begin(), names.end(), "mass") - names.begin()));
  long first = -1;
  double value = 0;
  for (long i = 0; i < 1000 && first < 0; ++i) {
    const double x = std::fma(600, rng.normal(), 1500);
    if (x <= 0) first = i, value = x;
  }
  REQUIRE(first > 0);
  const std::string m = thrown(s, 20000, 7);
  INFO(m);
  CHECK_THAT(m, Contains("'mass'") && Contains(fmt::format("value {} kg", value)) &&
                    Contains(fmt::format("vehicle {} ", first)) && Contains("seed 7") && Contains("narrower") &&
                    Contains("normal(mean 1500, sd 600)") && Contains("(0, 10000000] kg"));

  // A value in range that makes a vehicle failing validate: the tire's df0 below 2 fm / sm.
  const std::string t = thrown(spec(R"({"tire_cornering_scale": {"distribution": "uniform", "low": 0.3, "high": 0.5},
                      "mass": {"distribution": "normal", "mean": 2100, "sd": 10}})"),
                               20, 1);
  INFO(t);
  CHECK_THAT(t,
             Contains("'tire_cornering_scale'") && Contains("vehicle 0 ") && Contains("df0") && Contains("narrower"));

  // cg_to_front beyond the wheelbase leaves no cg_to_rear.
  const std::string c = thrown(spec(R"({"cg_to_front": {"distribution": "uniform", "low": 3.4, "high": 3.5}})"), 5, 1);
  CHECK_THAT(c, Contains("'cg_to_front'") && Contains("cg_to_rear"));
}

TEST_CASE("vary: more vehicles than the memory limit allows are refused before drawing", "[rom_batch_vary]") {
  const RomVehicle base = testing::hmmwv();
  const VarySpec s = spec(R"({"mass": {"distribution": "normal", "mean": 2100, "sd": 50}})");
  try {
    draw_vehicles(base, s, 10'000'000, 1);
    FAIL("no InputError");
  } catch (const InputError& e) {
    CHECK_THAT(std::string(e.what()),
               Catch::Contains("10000000 vehicles") && Catch::Contains("GiB") && Catch::Contains("limit of 8 GiB"));
  }
  const std::uint64_t limit = 10 * sizeof(RomVehicle);
  CHECK(draw_vehicles(base, s, 10, 1, limit).vehicles.size() == 10);
  CHECK_THROWS_AS(draw_vehicles(base, s, 11, 1, limit), InputError);
  CHECK_THROWS_AS(draw_vehicles(base, s, 0, 1), InputError);
}

namespace {

struct H5 {
  hid_t id;
  herr_t (*closer)(hid_t);
  ~H5() {
    if (id >= 0) closer(id);
  }
};

std::vector<hsize_t> shape_of(hid_t file, const char* name) {
  H5 ds{H5Dopen2(file, name, H5P_DEFAULT), H5Dclose};
  REQUIRE(ds.id >= 0);
  H5 space{H5Dget_space(ds.id), H5Sclose};
  const int rank = H5Sget_simple_extent_ndims(space.id);
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space.id, dims.data(), nullptr);
  H5 type{H5Dget_type(ds.id), H5Tclose};
  CHECK(H5Tequal(type.id, H5T_IEEE_F64LE) > 0);
  return dims;
}

std::vector<double> read_all(hid_t file, const char* name) {
  std::size_t n = 1;
  for (hsize_t d : shape_of(file, name)) n *= d;
  std::vector<double> v(n);
  H5 ds{H5Dopen2(file, name, H5P_DEFAULT), H5Dclose};
  if (n > 0) REQUIRE(H5Dread(ds.id, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) >= 0);
  return v;
}

std::string text_attribute(hid_t loc, const char* obj, const char* name) {
  H5 attr{H5Aopen_by_name(loc, obj, name, H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
  REQUIRE(attr.id >= 0);
  H5 type{H5Aget_type(attr.id), H5Tclose};
  std::string s(H5Tget_size(type.id), '\0');
  REQUIRE(H5Aread(attr.id, type.id, s.data()) >= 0);
  return s.substr(0, std::strlen(s.c_str()));
}

template <class T>
T number_attribute(hid_t file, const char* name, hid_t mem_type) {
  H5 attr{H5Aopen(file, name, H5P_DEFAULT), H5Aclose};
  REQUIRE(attr.id >= 0);
  T v{};
  REQUIRE(H5Aread(attr.id, mem_type, &v) >= 0);
  return v;
}

}  // namespace

TEST_CASE("batch.h5: shapes, attributes and transposed channels and final state", "[rom_batch_vary]") {
  constexpr long kV = 3;
  constexpr int kS = 4, kStates = 5;
  BatchOptions o;
  o.model = RomModel::k11Dof;
  o.step = 2e-3;
  o.end_time = 1.5;
  o.initial_speed = 7.0;
  o.output_rate = 10.0;
  o.channels = {kChVx, kChAy};
  BatchResult r;
  r.vehicles = kV;
  r.samples = kS;
  r.states = kStates;
  r.device = "CPU, 2 threads";
  r.failed = 1;
  r.metrics.resize(kBatchMetricCount * kV);
  for (int m = 0; m < kBatchMetricCount; ++m)
    for (long v = 0; v < kV; ++v) r.metrics[m * kV + v] = 10.0 * m + v;
  r.channels.resize(o.channels.size() * kS * kV);
  for (std::size_t c = 0; c < o.channels.size(); ++c)
    for (int s = 0; s < kS; ++s)
      for (long v = 0; v < kV; ++v) r.channels[(c * kS + s) * kV + v] = 100.0 * c + 10.0 * s + v;  // [c][s][v]
  r.final_state.resize(kStates * kV);
  for (int s = 0; s < kStates; ++s)
    for (long v = 0; v < kV; ++v) r.final_state[s * kV + v] = 1000.0 * s + v;  // [state][vehicle]

  const VaryDraws draws = draw_vehicles(testing::hmmwv(), spec(R"({
      "mass": {"distribution": "normal", "mean": 2100, "sd": 50},
      "friction": {"distribution": "uniform", "low": 0.5, "high": 1.0}})"),
                                        kV, 99);

  test::ScratchDir dir("batch_h5");
  const std::string path = dir.str() + "/batch.h5";
  write_batch_h5(path, r, o, &draws, {"", "hmmwv", 99});
  // Nothing but the file is left in the folder (the temporary was renamed).
  CHECK(std::distance(std::filesystem::directory_iterator(dir.path), std::filesystem::directory_iterator{}) == 1);

  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(file >= 0);
  H5 closer{file, H5Fclose};

  CHECK(shape_of(file, "time") == std::vector<hsize_t>{kS});
  CHECK(read_all(file, "time") == std::vector<double>{0 / 10.0, 1 / 10.0, 2 / 10.0, 3 / 10.0});  // k / output_rate

  CHECK(shape_of(file, "channels/vx") == std::vector<hsize_t>{kV, kS});
  CHECK(shape_of(file, "channels/ay") == std::vector<hsize_t>{kV, kS});
  const std::vector<double> ay = read_all(file, "channels/ay");
  const std::vector<double> vx = read_all(file, "channels/vx");
  for (long v = 0; v < kV; ++v)
    for (int s = 0; s < kS; ++s) {
      CHECK(vx[v * kS + s] == 10.0 * s + v);
      CHECK(ay[v * kS + s] == 100.0 + 10.0 * s + v);
    }
  CHECK(H5Lexists(file, "channels/x", H5P_DEFAULT) == 0);
  CHECK(text_attribute(file, "channels/ay", "units") == "m/s^2");

  CHECK(shape_of(file, "final_state") == std::vector<hsize_t>{kV, kStates});
  const std::vector<double> fs = read_all(file, "final_state");
  CHECK(fs[2 * kStates + 4] == 4002.0);  // vehicle 2, state 4
  CHECK(fs[1 * kStates + 0] == 1.0);

  for (int m = 0; m < kBatchMetricCount; ++m) {
    const std::string name = std::string("summary/") + kBatchMetricNames[m];
    CHECK(shape_of(file, name.c_str()) == std::vector<hsize_t>{kV});
    CHECK(read_all(file, name.c_str()) == std::vector<double>{10.0 * m, 10.0 * m + 1, 10.0 * m + 2});
  }
  CHECK(text_attribute(file, "summary/failed_at", "units") == "s");

  CHECK(read_all(file, "parameters/mass") == draws.values[index_of(draws, "mass")]);
  CHECK(read_all(file, "parameters/friction") == draws.values[index_of(draws, "friction")]);
  CHECK(text_attribute(file, "parameters/mass", "units") == "kg");
  CHECK(text_attribute(file, "parameters/friction", "distribution") == "uniform(low 0.5, high 1)");

  CHECK(text_attribute(file, ".", "model") == model_name(RomModel::k11Dof));
  CHECK(text_attribute(file, ".", "vehicle") == "hmmwv");
  CHECK(text_attribute(file, ".", "device") == "CPU, 2 threads");
  CHECK(number_attribute<double>(file, "step", H5T_NATIVE_DOUBLE) == 2e-3);
  CHECK(number_attribute<double>(file, "end_time", H5T_NATIVE_DOUBLE) == 1.5);
  CHECK(number_attribute<double>(file, "initial_speed", H5T_NATIVE_DOUBLE) == 7.0);
  CHECK(number_attribute<std::int64_t>(file, "vehicles", H5T_NATIVE_INT64) == kV);
  CHECK(number_attribute<std::uint64_t>(file, "seed", H5T_NATIVE_UINT64) == 99);
}

TEST_CASE("batch.h5: without draws or channels, inconsistent results are refused", "[rom_batch_vary]") {
  BatchOptions o;  // no output rate, no channels
  BatchResult r;
  r.vehicles = 2;
  r.states = 1;
  r.metrics.assign(kBatchMetricCount * 2, 0.5);
  r.final_state = {1.0, 2.0};
  test::ScratchDir dir("batch_h5_plain");
  const std::string path = dir.str() + "/b.h5";
  write_batch_h5(path, r, o, nullptr, {});
  {
    const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    REQUIRE(file >= 0);
    H5 closer{file, H5Fclose};
    CHECK(shape_of(file, "time") == std::vector<hsize_t>{0});
    CHECK(read_all(file, "final_state") == std::vector<double>{1.0, 2.0});
    H5G_info_t info;
    H5 params{H5Gopen2(file, "parameters", H5P_DEFAULT), H5Gclose};
    REQUIRE(H5Gget_info(params.id, &info) >= 0);
    CHECK(info.nlinks == 0);
    CHECK(text_attribute(file, ".", "model") == model_name(o.model));
  }
  BatchResult bad = r;
  bad.metrics.pop_back();
  const std::string bad_path = dir.str() + "/bad.h5";
  CHECK_THROWS_WITH(write_batch_h5(bad_path, bad, o, nullptr, {}), Catch::Contains("summary metrics"));
  bad = r;
  bad.samples = 3;
  o.channels = {kChX};
  CHECK_THROWS_AS(write_batch_h5(bad_path, bad, o, nullptr, {}), RunError);
  CHECK_FALSE(std::filesystem::exists(bad_path));
  CHECK(std::distance(std::filesystem::directory_iterator(dir.path), std::filesystem::directory_iterator{}) == 1);
}
