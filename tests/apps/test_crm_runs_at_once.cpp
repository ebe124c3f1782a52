// CRM runs at once (--concurrent-runs, apps/rig_runs.cpp): a wheel sweep and a bevameter run with
// several runs at once give what they give one run at a time. On the CPU (CI) the engine is
// deterministic, so the curves must be equal to the last bit; with TERRACAL_TEST_DEVICE=cuda the same
// runs go to the GPU, each on its own thread's stream, where the wrench sums' atomics already make two
// runs of one binary differ in the last digits: there they must agree to 1e-3 (a shared scratch
// buffer or a stream mix-up would move them by far more).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "apps/rig_runs.hpp"
#include "tests/highfi/crm/crm_test_scenes.hpp"

using namespace terracal;

namespace {
app::TerrainOptions tiny_crm(int at_once) {
  app::TerrainOptions o;
  o.spacing = 0.02;
  o.device = test::validation_device() == CrmDevice::kCuda ? app::DeviceChoice::kCuda : app::DeviceChoice::kCpu;
  o.cache = "";
  o.settle_time = 0.05;
  o.concurrent_runs = at_once;
  return o;
}

app::SoilChoice crm_soil() {
  app::SoilChoice s;
  s.solver = app::SoilModel::kCrm;
  s.crm = CrmSoil{};  // bevameter study soil (2022)
  return s;
}

bool gpu() { return test::validation_device() == CrmDevice::kCuda; }

void check_same(double a, double b, const char* what) {
  INFO(what << ": " << a << " against " << b);
  if (gpu())
    CHECK(std::abs(a - b) <= 1e-3 * std::max(std::abs(a), std::abs(b)) + 1e-9);
  else
    CHECK(a == b);
}
}  // namespace

TEST_CASE("CRM wheel sweep: runs at once give the runs one at a time", "[apps][crm][concurrent]") {
  rigs::WheelSpec wheel;
  wheel.radius = 0.08;
  wheel.width = 0.06;
  wheel.mass = 2;
  wheel.angular_velocity = 1;
  rigs::WheelRun run;
  run.duration = 0.08;
  run.samples = 20;
  const std::vector<double> slips{0.1, 0.4, 0.7};
  const auto one = app::run_wheel_sweep(app::SoilModel::kCrm, crm_soil(), tiny_crm(1), wheel, slips, run);
  const auto three = app::run_wheel_sweep(app::SoilModel::kCrm, crm_soil(), tiny_crm(3), wheel, slips, run);
  REQUIRE(one.size() == slips.size());
  REQUIRE(three.size() == slips.size());
  for (std::size_t i = 0; i < slips.size(); ++i) {
    INFO("slip " << slips[i]);
    CHECK(three[i].slip == slips[i]);
    check_same(one[i].dbp, three[i].dbp, "DBP");
    check_same(one[i].torque, three[i].torque, "torque");
    check_same(one[i].sinkage, three[i].sinkage, "sinkage");
    REQUIRE(one[i].series.size() == three[i].series.size());
    check_same(one[i].series.back().vertical, three[i].series.back().vertical, "last vertical force");
  }
  // The slips are different runs: the sweep did not hand one slip's result to another.
  CHECK(one[0].torque != one[2].torque);
}

TEST_CASE("CRM bevameter: plates and annulus loads at once give them one at a time", "[apps][crm][concurrent]") {
  app::BevameterPlan plan;
  plan.plates = {0.04, 0.06};
  plan.max_sinkage = 0.01;
  plan.plate_wall_radii = 3;
  plan.plate_depth_scale = 1;
  plan.inner_radius = 0.03;
  plan.outer_radius = 0.05;
  plan.shear_loads = {10, 30};
  plan.shear_angle = 0.04;
  plan.shear_settle = 0.03;
  plan.bin_scale = 0.5;
  const auto one = app::run_bevameter(crm_soil(), tiny_crm(1), plan, true, true);
  const auto all = app::run_bevameter(crm_soil(), tiny_crm(4), plan, true, true);
  REQUIRE(one.plate.size() == all.plate.size());
  REQUIRE(one.shear.size() == all.shear.size());
  REQUIRE(!one.plate.empty());
  REQUIRE(!one.shear.empty());
  for (std::size_t i = 0; i < one.plate.size(); ++i) {
    INFO("plate row " << i);
    CHECK(one.plate[i].radius == all.plate[i].radius);
    CHECK(one.plate[i].phase == all.plate[i].phase);
    check_same(one.plate[i].force, all.plate[i].force, "plate force");
  }
  for (std::size_t i = 0; i < one.shear.size(); ++i) {
    INFO("shear row " << i);
    CHECK(one.shear[i].normal_load == all.shear[i].normal_load);
    check_same(one.shear[i].torque, all.shear[i].torque, "torque");
  }
  CHECK(one.site == all.site);
  // The rows keep the plan's order: plates as listed, then the loads.
  CHECK(all.plate.front().radius == 0.04);
  CHECK(all.plate.back().radius == 0.06);
  CHECK(all.shear.front().normal_load == 10);
  CHECK(all.shear.back().normal_load == 30);
}
