// `terracal wheel-table` and the deformable_terrain effect on tables of real SCM runs: the grid
// equals single rig runs, its trends are the soil's (pull grows with slip and load, a slip angle
// pulls the wheel back across), and on a very stiff soil's table the ROM accelerates as on rigid
// ground. The command end to end, and `terracal rom --terrain-table` on its table.
#include <cmath>

#include <catch2/catch.hpp>

#include "apps/wheel_table.hpp"
#include "lowfi/scm_soil.hpp"
#include "rom/rom_run.hpp"
#include "tests/apps/cli_runner.hpp"
#include "tests/rom/rom_test_vehicles.hpp"

using namespace terracal;


namespace {

app::SoilChoice scm_choice(const lowfi::ScmSoil& soil) {
  app::SoilChoice c;
  c.solver = app::SoilModel::kScm;
  c.scm = soil;
  return c;
}

app::TerrainOptions scm_options(double grid) {
  app::TerrainOptions o;
  o.grid = grid;
  o.step = 1e-3;
  return o;
}

}  // namespace

TEST_CASE("wheel-table: the grid equals single rig runs and follows the soil's trends", "[wheel-table]") {
  const lowfi::ScmSoil sand = lowfi::reference_dry_sand();
  const app::TerrainOptions o = scm_options(0.02);
  rigs::WheelSpec wheel;  // r 0.47 m, b 0.25 m
  app::WheelTablePlan plan;
  plan.loads = {1000, 2000};
  plan.slips = {0, 0.2, 0.5};
  plan.angles = {0, 0.15};
  plan.run.duration = 1.5;
  const rom::TerrainTable t = app::run_wheel_table(scm_choice(sand), o, wheel, plan);
  REQUIRE(t.dbp.size() == 12);
  // One point run alone, on a site of its own: the same steady means to the last bit.
  rigs::WheelSpec w = wheel;
  w.mass = 2000 / 9.81;
  rigs::WheelRun run = plan.run;
  run.slip_angle = 0.15;
  const auto site = app::wheel_site(scm_choice(sand), o, wheel, plan.slips, run);
  const rigs::WheelResult single = rigs::run_wheel(*site, w, 0.2, run);
  CHECK(t.dbp[t.index(1, 1, 1)] == single.dbp);
  CHECK(t.lateral[t.index(1, 1, 1)] == single.lateral);
  for (std::size_t l = 0; l < 2; ++l) {
    INFO("load " << t.load[l] << " N: DBP " << t.dbp[t.index(l, 0, 0)] << ", " << t.dbp[t.index(l, 1, 0)] << ", "
                 << t.dbp[t.index(l, 2, 0)] << " N; lateral at 0 / 0.15 rad " << t.lateral[t.index(l, 1, 0)] << " / "
                 << t.lateral[t.index(l, 1, 1)] << " N");
    // Pull and torque grow with slip; a towed wheel (slip 0) meets resistance.
    CHECK(t.dbp[t.index(l, 0, 0)] < 0);
    CHECK(t.dbp[t.index(l, 1, 0)] > t.dbp[t.index(l, 0, 0)]);
    CHECK(t.dbp[t.index(l, 2, 0)] > t.dbp[t.index(l, 1, 0)]);
    CHECK(t.torque[t.index(l, 2, 0)] > t.torque[t.index(l, 1, 0)]);
    // Straight ahead no side force; at a slip angle the soil pushes against the sideways motion (+y),
    // by a good part of the load.
    CHECK(std::fabs(t.lateral[t.index(l, 1, 0)]) < 0.02 * t.load[l]);
    CHECK(t.lateral[t.index(l, 1, 1)] < -0.1 * t.load[l]);
  }
  // More load: deeper, and more torque at the same slip.
  CHECK(t.sinkage[t.index(1, 1, 0)] > t.sinkage[t.index(0, 1, 0)]);
  CHECK(t.torque[t.index(1, 1, 0)] > t.torque[t.index(0, 1, 0)]);
}

// On a soil stiff enough to carry the HMMWV on millimetres, the table's forces are those of a tire
// on hard ground: the deformable_terrain ROM's straight-line acceleration equals the rigid-ground
// ROM's within 5 %.
TEST_CASE("deformable_terrain on a very stiff soil's table accelerates as on rigid ground", "[wheel-table][rom]") {
  lowfi::ScmSoil stiff;
  stiff.Kphi = 2e10;
  stiff.Kc = 0;
  stiff.n = 1.0;
  stiff.cohesion = 0;
  stiff.friction_deg = 40;
  stiff.janosi_k = 2e-4;
  stiff.elastic_stiffness = 1e11;
  rigs::WheelSpec wheel;
  rom::RomVehicle rigid = rom::testing::hmmwv();
  wheel.radius = rigid.tire[0].unloaded_radius;
  wheel.width = 0.3;
  wheel.angular_velocity = 2.0;
  app::WheelTablePlan plan;
  plan.loads = {4000, 8000};
  plan.slips = {0, 0.02, 0.05, 0.1, 0.2, 0.4};
  plan.run.duration = 1.0;
  const rom::TerrainTable t = app::run_wheel_table(scm_choice(stiff), scm_options(0.005), wheel, plan);
  for (std::size_t s = 0; s < t.slip.size(); ++s)
    INFO("slip " << t.slip[s] << ": thrust/Fz " << t.thrust[t.index(0, s, 0)] << ", resistance/Fz "
                 << t.resistance[t.index(0, s, 0)] << ", sinkage " << t.sinkage[t.index(0, s, 0)] << " m");
  CHECK(t.sinkage[t.index(1, 2, 0)] < 0.005);
  rom::RomVehicle soft = rigid;
  soft.terrain = t.view();
  soft.effects |= rom::kEffectDeformableTerrain;
  const DriverSeries go = rom::testing::constant_inputs(0, 0.4, 0);
  for (rom::RomModel m : {rom::RomModel::k11Dof, rom::RomModel::k18Dof}) {
    const double v0 = 3, end = 6;
    const double dv_rigid = rom::testing::run(rigid, go, rom::testing::options(m, end, v0)).samples.back().vx - v0;
    const double dv_table = rom::testing::run(soft, go, rom::testing::options(m, end, v0)).samples.back().vx - v0;
    INFO(rom::model_name(m) << ": speed gained in " << end << " s: rigid " << dv_rigid << " m/s, stiff soil's table "
                            << dv_table << " m/s");
    CHECK(std::fabs(dv_table - dv_rigid) < 0.05 * dv_rigid);
  }
}

TEST_CASE("terracal wheel-table writes a table that terracal rom --terrain-table drives on", "[cli][wheel-table]") {
  const test::ScratchDir dir("cli_wheel_table");
  test::write(dir.str() + "/wheel.json", R"({"radius": 0.47, "width": 0.25, "mass": 108, "angular_velocity": 1.0})");
  const test::CliResult r = test::run_cli("wheel-table --scm " + test::demo_data("truth.json") + " --wheel " +
                                              dir.str() + "/wheel.json --loads 3000,6000 --slips 0,0.1,0.3 --duration "
                                              "0.5 --grid 0.03 --out " +
                                              dir.str() + "/t/table.h5",
                                          dir.str());
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("2 loads x 3 slips x 1 slip angles (6 runs)") != std::string::npos);
  const rom::TerrainTable t = rom::read_terrain_table(dir.str() + "/t/table.h5");
  CHECK(t.load == std::vector<double>{3000, 6000});
  CHECK(t.soil == test::demo_data("truth.json"));
  test::write(dir.str() + "/m.json",
              R"({"type": "step_steer", "steering": 0.1, "step_time": 0.5, "initial_speed": 5, "end_time": 1.5})");
  const test::CliResult rom = test::run_cli("rom --model 18dof --vehicle hmmwv --maneuver " + dir.str() +
                                                "/m.json --no-plots --terrain-table " + dir.str() +
                                                "/t/table.h5 --out " + dir.str() + "/rom",
                                            dir.str());
  INFO(rom.err);
  CHECK(rom.exit_code == 0);
}
