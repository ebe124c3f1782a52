// The deformable_terrain effect's table: lookups against the formulas a table was made from, its
// conventions near zero slip and beyond its ends, the HDF5 file read back and refused when broken,
// and a ROM driving on it (slower than on rigid ground, held at standstill, CPU and GPU alike).
#include <cmath>
#include <filesystem>

#include <hdf5.h>
#include <hdf5_hl.h>

#include <catch2/catch.hpp>

#include "core/errors.hpp"
#include "rom/rom_batch.hpp"
#include "rom/wheel_contact.hpp"
#include "tests/rom/rom_test_vehicles.hpp"
#include "tests/rom/terrain_tables.hpp"
#include "tests/scratch_dir.hpp"
#include "tests/skip.hpp"

using namespace terracal;
using namespace terracal::rom;
using namespace terracal::rom::testing;
using Catch::Matchers::Contains;

namespace {
// The rig's slips as TMeasy's (sx, sy) for a slip s and a slip angle alpha (rom/terrain_table.hpp).
double sy_of(double s, double alpha) { return -(1 - s) * std::tan(alpha); }
}  // namespace

TEST_CASE("terrain table: lookups equal the formulas at the grid, interpolate between, mirror and clamp",
          "[rom][terrain]") {
  TableFormula f;
  f.h0 = 0.12;  // a rolling wheel's thrust without slip, as SCM's rut gives it
  const TerrainTable t = formula_table(f);
  const TerrainTableView v = t.view();
  auto thrust = [&](double fz, double sx, double sy = 0) {
    const SoilTireForces r = soil_tire_forces(v, fz, sx, sy);
    return r.thrust0 + r.slip_thrust;
  };
  // At grid points the formula itself, forces proportional to the load.
  for (double fz : {2000.0, 4000.0})
    for (double s : {0.05, 0.2, 0.4}) {
      const SoilTireForces r = soil_tire_forces(v, fz, s, 0.0);
      CHECK(r.thrust0 == Approx(fz * f.h0).epsilon(1e-12));
      CHECK(thrust(fz, s) == Approx(fz * f.thrust(s)).epsilon(1e-12));
      CHECK(r.resistance == Approx(fz * f.resistance(s)).epsilon(1e-12));
      CHECK(std::fabs(r.fy) < 1e-9 * fz);
    }
  // Linear between grid slips, and between loads (per unit load); the slip's part is zero at zero.
  CHECK(thrust(4000, 0.3) == Approx(2000 * (f.thrust(0.2) + f.thrust(0.4))).epsilon(1e-12));
  CHECK(thrust(3000, 0.2) == Approx(3000 * f.thrust(0.2)).epsilon(1e-12));
  CHECK(soil_tire_forces(v, 4000, 0.0, 0.0).slip_thrust == 0.0);
  // Without negative slips the table mirrors: from the first slip above zero (0.02) on, a braked
  // wheel's thrust is the driven one's turned round; below it, linear from H(0); the resistance stays.
  CHECK(thrust(4000, -0.2) == Approx(-4000 * f.thrust(0.2)).epsilon(1e-12));
  CHECK(thrust(4000, -0.02) == Approx(-4000 * f.thrust(0.02)).epsilon(1e-12));
  CHECK(thrust(4000, -0.01) == Approx(4000 * (f.h0 - 0.5 * (f.h0 + f.thrust(0.02)))).epsilon(1e-12));
  CHECK(soil_tire_forces(v, 4000, -0.2, 0).resistance == Approx(4000 * f.resistance(0.2)).epsilon(1e-12));
  // Beyond the ends: the nearest entry per unit load (loads 500 and 20,000; slip 0.95).
  CHECK(thrust(500, 0.2) == Approx(500 * f.thrust(0.2)).epsilon(1e-12));
  CHECK(thrust(20000, 0.2) == Approx(20000 * f.thrust(0.2)).epsilon(1e-12));
  CHECK(thrust(4000, 0.95) == Approx(4000 * f.thrust(0.8)).epsilon(1e-12));
  // Lateral: against the sideways velocity, the formula at the grid angles, linear below the first.
  for (double a : {0.1, 0.2}) {
    CHECK(soil_tire_forces(v, 4000, 0.2, sy_of(0.2, a)).fy == Approx(4000 * f.lateral(a)).epsilon(1e-9));
    CHECK(soil_tire_forces(v, 4000, 0.2, sy_of(0.2, -a)).fy == Approx(-4000 * f.lateral(a)).epsilon(1e-9));
  }
  CHECK(soil_tire_forces(v, 4000, 0.0, sy_of(0.0, 0.025)).fy == Approx(0.5 * 4000 * f.lateral(0.05)).epsilon(1e-3));
  // No load, no force.
  const SoilTireForces off = soil_tire_forces(v, 0, 0.2, 0.1);
  CHECK(off.slip_thrust == 0);
  CHECK(off.thrust0 == 0);
  CHECK(off.fy == 0);
  CHECK(off.resistance == 0);
}

// A rolling tire on the table is the rig's wheel: its force on the chassis is the drawbar pull,
// the force that turns it (times the radius, the torque) is the thrust; at rest neither the
// zero-slip thrust nor the resistance acts.
TEST_CASE("deformable_terrain: a rolling tire pushes the chassis with DP and loads its spin with T / r",
          "[rom][terrain]") {
  TableFormula f;
  f.h0 = 0.12;
  const TerrainTable t = formula_table(f);
  RomVehicle v = hmmwv();
  v.effects = (v.effects | kEffectDeformableTerrain) & ~kEffectTireRelaxation;
  v.terrain = t.view();
  const double fz = 4000, vx = 5;
  const double rdyn = wheel_contact(v, v.tire[0], fz, vx, 0, 10, 0, 0, 1.0).rdyn;  // set by the load alone
  for (double s : {0.05, 0.2, 0.4}) {
    // The spin at which TMeasy's slip (rdyn omega - vx) / (rdyn omega + vN) is the grid's s.
    const double omega = (vx + s * kTmeasySlipVelocity) / (rdyn * (1 - s));
    const WheelContact w = wheel_contact(v, v.tire[0], fz, vx, 0, omega, 0, 0, 1.0);
    INFO("slip " << s);
    CHECK(w.fx == Approx(fz * f.thrust(s)).epsilon(1e-9));
    CHECK(w.fx + w.resist == Approx(fz * (f.thrust(s) - f.resistance(s))).epsilon(1e-9));
  }
  const WheelContact rest = wheel_contact(v, v.tire[0], fz, 0, 0, 0, 0, 0, 1.0);
  CHECK(rest.fx == 0);
  CHECK(rest.resist == 0);
}

TEST_CASE("terrain table: the HDF5 file reads back; a broken one is refused naming what is wrong", "[rom][terrain]") {
  const test::ScratchDir scratch("terrain_table");
  const std::string dir = scratch.str();
  const TerrainTable t = formula_table();
  const std::string path = dir + "/t.h5";
  write_terrain_table(path, t);
  const TerrainTable back = read_terrain_table(path);
  CHECK(back.load == t.load);
  CHECK(back.slip == t.slip);
  CHECK(back.angle == t.angle);
  CHECK(back.dbp == t.dbp);
  CHECK(back.torque == t.torque);
  CHECK(back.lateral == t.lateral);
  CHECK(back.thrust == t.thrust);
  CHECK(back.radius == t.radius);

  CHECK_THROWS_WITH(read_terrain_table(dir + "/none.h5"), Contains("none.h5") && Contains("cannot open"));
  TerrainTable bad = t;
  bad.slip[2] = bad.slip[1];
  CHECK_THROWS_AS(write_terrain_table(dir + "/bad.h5", bad), InputError);
  CHECK_THROWS_WITH(write_terrain_table(dir + "/bad.h5", bad), Contains("slip") && Contains("increase"));
  CHECK_FALSE(std::filesystem::exists(dir + "/bad.h5"));
  // A file whose dataset was removed, and one whose slips were made to decrease.
  {
    const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    REQUIRE(f >= 0);
    REQUIRE(H5Ldelete(f, "lateral_N", H5P_DEFAULT) >= 0);
    H5Fclose(f);
  }
  CHECK_THROWS_WITH(read_terrain_table(path), Contains("t.h5") && Contains("lateral_N"));
  write_terrain_table(path, t);
  {
    const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    std::vector<double> s = t.slip;
    std::swap(s[1], s[2]);
    const hid_t ds = H5Dopen2(f, "slip", H5P_DEFAULT);
    REQUIRE(H5Dwrite(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, s.data()) >= 0);
    H5Dclose(ds);
    H5Fclose(f);
  }
  CHECK_THROWS_AS(read_terrain_table(path), InputError);
  CHECK_THROWS_WITH(read_terrain_table(path), Contains("slip") && Contains("entry 2"));
}

TEST_CASE("deformable_terrain: needs a table; on a soft table the HMMWV accelerates less and stands still at rest",
          "[rom][terrain]") {
  RomVehicle v = hmmwv();
  v.effects |= kEffectDeformableTerrain;
  const DriverSeries go = constant_inputs(0, 0.5, 0);
  CHECK_THROWS_WITH(run(v, go, options(RomModel::k18Dof, 1, 0)), Contains("deformable_terrain") &&
                                                                      Contains("--terrain-table"));
  TableFormula f;
  f.h0 = 0.12;  // a rolling wheel's thrust without slip: it must not push a vehicle at rest
  const TerrainTable t = formula_table(f);
  v.terrain = t.view();
  for (RomModel m : {RomModel::k11Dof, RomModel::k18Dof}) {
    INFO(model_name(m));
    const RomRunResult rigid = run(hmmwv(), go, options(m, 5, 2));
    const RomRunResult soft = run(v, go, options(m, 5, 2));
    const double dv_rigid = rigid.samples.back().vx - 2, dv_soft = soft.samples.back().vx - 2;
    INFO("speed gained in 5 s: rigid " << dv_rigid << " m/s, soft table " << dv_soft << " m/s");
    CHECK(dv_soft > 0);
    CHECK(dv_soft < dv_rigid);
    // Standstill without throttle: the resistance holds the wheels, nothing pushes.
    const RomRunResult rest = run(v, constant_inputs(0, 0, 0), options(m, 2, 0));
    for (const auto& s : rest.samples) {
      REQUIRE(std::isfinite(s.x));
      CHECK(std::fabs(s.x) < 1e-6);
    }
  }
}

// A soil whose shear saturates early (small Janosi k): the rut's thrust H(0) is larger than what slip
// adds to it. Mirroring only the slip's part for braking left the thrust positive at every braking
// slip, so a coasting wheel had no rolling equilibrium: it spun backwards and the HMMWV, throttle on,
// crawled to a stop before it could accelerate (a campaign's calibrated dry sand did this).
TEST_CASE("deformable_terrain: on a table whose thrust saturates early, a coasting wheel keeps rolling forward",
          "[rom][terrain]") {
  TableFormula f;
  f.h0 = 0.31, f.mu = 0.2, f.s0 = 0.02;  // H/Fz from 0.31 at zero slip to 0.51
  const TerrainTable t = formula_table(f);
  const TerrainTableView tv = t.view();
  // Braked hard, the wheel is pushed back by the turned-round shear; the thrust changes sign once.
  const SoilTireForces locked = soil_tire_forces(tv, 4000, -0.8, 0);
  CHECK(locked.thrust0 + locked.slip_thrust == Approx(-4000 * f.thrust(0.8)).epsilon(1e-12));
  int sign_changes = 0;
  double last = f.h0;
  for (double sx = -0.001; sx > -0.1; sx -= 0.001) {
    const SoilTireForces r = soil_tire_forces(tv, 4000, sx, 0);
    const double h = r.thrust0 + r.slip_thrust;
    sign_changes += (h < 0) != (last < 0);
    last = h;
  }
  CHECK(sign_changes == 1);
  RomVehicle v = hmmwv();
  v.effects |= kEffectDeformableTerrain;
  v.terrain = tv;
  // Coasting at 2 m/s for half a second, then throttle 0.5.
  const DriverSeries drive = DriverSeries::from_rows({0.0, 0.5, 0.51, 8.0}, {0, 0, 0, 0}, {0, 0, 0.5, 0.5}, {0, 0, 0, 0});
  for (RomModel m : {RomModel::k11Dof, RomModel::k18Dof}) {
    INFO(model_name(m));
    const RomRunResult r = run(v, drive, options(m, 8, 2));
    double v1 = NAN, v3 = NAN;
    for (const auto& s : r.samples) {
      REQUIRE(std::isfinite(s.vx));
      if (std::fabs(s.time - 1) < 1e-9) v1 = s.vx;
      if (std::fabs(s.time - 3) < 1e-9) v3 = s.vx;
    }
    INFO("vx at 1 s " << v1 << ", 3 s " << v3 << ", 8 s " << r.samples.back().vx << " m/s");
    CHECK(v3 > v1);
    CHECK(r.samples.back().vx > 2);
  }
}

TEST_CASE("deformable_terrain: the GPU batch equals the CPU batch on a table", "[rom][terrain][gpu]") {
  if (!test::cuda_device_or_skip("deformable_terrain GPU/CPU agreement")) return;
  const TerrainTable t = formula_table();
  std::vector<RomVehicle> vs(64, hmmwv());
  for (std::size_t i = 0; i < vs.size(); ++i) {
    vs[i].terrain = t.view();
    vs[i].effects |= kEffectDeformableTerrain;
    vs[i].max_steer *= 0.5 + double(i) / vs.size();
  }
  const DriverSeries d = DriverSeries::from_rows({0, 1, 2, 3}, {0, 0.3, 0.3, -0.2}, {0.3, 0.6, 0.4, 0.2}, {0, 0, 0, 0.3});
  BatchOptions o;
  o.end_time = 3;
  o.initial_speed = 5;
  o.channels = {kChVx, kChYawRate, kChAy};
  for (RomModel m : {RomModel::k11Dof, RomModel::k18Dof}) {
    o.model = m;
    o.device = BatchDevice::kCpu;
    const BatchResult cpu = run_rom_batch(vs, {&d}, long(vs.size()), o);
    o.device = BatchDevice::kCuda;
    const BatchResult gpu = run_rom_batch(vs, {&d}, long(vs.size()), o);
    REQUIRE(cpu.failed == 0);
    CHECK(gpu.failed == 0);
    double worst = 0;
    for (std::size_t k = 0; k < cpu.channels.size(); ++k)
      worst = std::max(worst, std::fabs(gpu.channels[k] - cpu.channels[k]) / std::max(1.0, std::fabs(cpu.channels[k])));
    INFO(model_name(m) << ": largest relative difference " << worst);
    CHECK(worst < 1e-10);
  }
}
