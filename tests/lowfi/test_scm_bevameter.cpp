// The SCM terrain driven by the plate and annulus rigs reproduces the analytic
// bevameter laws (the forward models of the calibrator), its unload slope is the elastic stiffness,
// and calibrating on its curves recovers the soil.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "bayes/calibration_problem.hpp"
#include "bayes/forward_models.hpp"
#include "bayes/observations.hpp"
#include "bayes/point_estimate.hpp"
#include "scm_test_soils.hpp"
#include "tests/scratch_dir.hpp"
#include "virtual_bevameter/plate_rig.hpp"
#include "virtual_bevameter/shear_rig.hpp"

using namespace terracal;

namespace {
double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

// The annulus tests' site (0.005 m grid, damping, so the ring comes to rest) and rig: loads of 200
// and 800 N, settled for `settle` s, turned to `max_angle` rad.
lowfi::ScmSite annulus_site(const lowfi::ScmSoil& soil) { return test::scm_site(soil, 0.005, 1e-3, {"damping"}); }
rigs::ShearTest annulus_test(double settle, double max_angle) {
  rigs::ShearTest t;
  t.settle_time = settle;
  t.loads = {200, 800};
  t.max_angle = max_angle;
  return t;
}
}  // namespace

TEST_CASE("SCM plate rig: loading follows Bekker within 2 %, unloading has slope Ke A", "[lowfi][scm]") {
  const lowfi::ScmSoil soil = test::scm_dry_sand();
  for (double r : {0.1, 0.2}) {
    // 40 grid cells across the radius: the lattice area of the plate is within 0.5 % of pi r^2.
    const auto site = test::scm_site(soil, r / 40, 1e-3);
    rigs::PlateTest t;
    t.radius = r;
    t.max_sinkage = 0.1;
    t.speed = 0.1;
    const auto rows = rigs::run_plate(site, t);
    double worst = 0, deepest = 0;
    int loads = 0;
    for (const auto& row : rows) {
      // Reloading climbs the unload line back to the previous deepest point (the soil followed the
      // plate up as it left), then follows the virgin curve; two samples' margin for the transition.
      const double transition = 2 * t.max_sinkage / t.samples;
      const bool plastic = row.phase == "load" || (row.phase == "reload" && row.sinkage > deepest + transition);
      if (row.phase != "reload") deepest = std::max(deepest, row.sinkage);
      if (!plastic || row.sinkage < 0.01) continue;
      const double analytic = M_PI * r * r * (soil.Kc / r + soil.Kphi) * std::pow(row.sinkage, soil.n);
      worst = std::max(worst, rel(row.force, analytic));
      ++loads;
    }
    INFO("plate r = " << r << ": " << loads << " loading rows, worst relative error " << worst);
    CHECK(loads > 50);
    CHECK(worst < 0.02);
    // Unload: the force falls along Ke x (contact area) until the plate leaves the soil.
    std::vector<std::pair<double, double>> unload;
    for (const auto& row : rows)
      if (row.phase == "unload" && row.force > 0) unload.push_back({row.sinkage, row.force});
    REQUIRE(unload.size() >= 3);
    // The slope between a branch's first and last rows (sinkage, force).
    auto slope_of = [](const std::vector<std::pair<double, double>>& b) {
      return (b.back().second - b.front().second) / (b.back().first - b.front().first);
    };
    const double slope = slope_of(unload);
    INFO("unload slope " << slope << " N/m against Ke pi r^2 = " << soil.elastic_stiffness * M_PI * r * r);
    CHECK(rel(slope, soil.elastic_stiffness * M_PI * r * r) < 0.02);
    // Reload: from where the plate left the soil, up the same line to the previous deepest point.
    double cycle_top = 0;  // where the unload began
    for (const auto& row : rows) {
      if (row.phase == "unload") break;
      cycle_top = std::max(cycle_top, row.sinkage);
    }
    std::vector<std::pair<double, double>> reload;
    for (const auto& row : rows)
      if (row.phase == "reload" && row.force > 0 && row.sinkage < cycle_top - 0.5 * t.max_sinkage / t.samples)
        reload.push_back({row.sinkage, row.force});
    REQUIRE(reload.size() >= 3);
    const double reload_slope = slope_of(reload);
    INFO("reload slope " << reload_slope << " N/m from " << reload.front().first << " m (unload reached "
                         << unload.back().first << " m)");
    CHECK(rel(reload_slope, soil.elastic_stiffness * M_PI * r * r) < 0.02);
    CHECK(std::abs(reload.front().first - unload.back().first) <
          2 * t.max_sinkage / t.samples);  // touches where the unload left
  }
}

TEST_CASE("SCM plate rig: a slower unload samples the same elastic line more densely and ends the same stroke",
          "[lowfi][scm]") {
  // SCM's plate is rate-independent: at a tenth of the speed the cycle's slope is still Ke A, the
  // branch holds several times the rows (the rows are spread over a longer stroke), and the stroke
  // still ends at the maximum sinkage.
  const lowfi::ScmSoil soil = test::scm_dry_sand();
  const double r = 0.1;
  const auto site = test::scm_site(soil, r / 40, 1e-3);
  rigs::PlateTest t;
  t.radius = r;
  t.max_sinkage = 0.1;
  t.speed = 0.1;
  t.samples = 1000;
  auto unload_of = [](const std::vector<rigs::PlateRow>& rows) {
    std::vector<std::pair<double, double>> b;
    for (const auto& row : rows)
      if (row.phase == "unload" && row.force > 0) b.push_back({row.sinkage, row.force});
    return b;
  };
  const auto fast = rigs::run_plate(site, t);
  t.unload_speed = 0.01;
  const auto slow = rigs::run_plate(site, t);
  const auto bf = unload_of(fast), bs = unload_of(slow);
  REQUIRE(bf.size() >= 3);
  INFO("unload rows: " << bf.size() << " at 0.1 m/s, " << bs.size() << " at 0.01 m/s");
  CHECK(bs.size() > 3 * bf.size());
  const double slope = (bs.back().second - bs.front().second) / (bs.back().first - bs.front().first);
  INFO("slow unload slope " << slope << " N/m against Ke pi r^2 = " << soil.elastic_stiffness * M_PI * r * r);
  CHECK(rel(slope, soil.elastic_stiffness * M_PI * r * r) < 0.02);
  CHECK(slow.back().sinkage == Approx(t.max_sinkage).margin(1e-3));
  CHECK(rel(slow.back().force, fast.back().force) < 0.01);
  // The unload starts where the fast one did: only the cycle's speed changed.
  CHECK(bs.front().first == Approx(bf.front().first).margin(2e-3));
}

TEST_CASE("SCM annulus rig: torque against angle follows the analytic annulus within 2 %", "[lowfi][scm]") {
  const lowfi::ScmSoil soil = test::scm_dry_sand();
  // Damping lets the annulus come to rest on its elastic bed before it turns; the damping is weak
  // (about 6 % of critical at 800 N), so the annulus settles for 2 s: after 0.3 s the left-over bounce
  // still moves the torque at small angles by 7 %.
  const auto site = annulus_site(soil);
  rigs::ShearTest t = annulus_test(2.0, 0.8);
  const auto rows = rigs::run_shear(site, t);
  int checked = 0;
  double worst = 0;
  for (const auto& row : rows) {
    if (row.angle < 0.02) continue;
    const double analytic = bayes::annulus_torque(t.inner_radius, t.outer_radius, row.normal_load, row.angle,
                                                  soil.cohesion, soil.friction_deg, soil.janosi_k);
    worst = std::max(worst, rel(row.torque, analytic));
    ++checked;
  }
  INFO(checked << " rows, worst relative error " << worst);
  CHECK(checked > 100);
  CHECK(worst < 0.02);
}

// A dead load dropped at once drives the ring past its static sinkage (SCM remembers the plastic
// part) and leaves it bouncing; put on gradually it comes to rest where Bekker's law carries it,
// z = (W / (A (Kc/b + Kphi)))^(1/n). The CRM annulus shows the same (results/plate_bin_check,
// twelfth study), which is why the bevameter and pipeline commands ramp the load by default
// (--shear-load-ramp 0.5; ShearTest itself drops it unless told otherwise).
TEST_CASE("SCM annulus under a ramped load rests at Bekker's static sinkage, a dropped one overshoots",
          "[lowfi][scm]") {
  const lowfi::ScmSoil soil = test::scm_dry_sand();
  const auto site = annulus_site(soil);
  rigs::ShearTest t = annulus_test(1.0, 0.05);
  auto first_sinkage = [&](double ramp) {
    t.load_ramp = ramp;
    const auto rows = rigs::run_shear(site, t);
    const auto heavy =
        std::find_if(rows.begin(), rows.end(), [](const rigs::ShearRow& r) { return r.normal_load == 800; });
    REQUIRE(heavy != rows.end());
    return std::pair{rows.front().sinkage, heavy->sinkage};  // 200 N, 800 N at the start of the turn
  };
  const auto [ramped200, ramped800] = first_sinkage(0.5);
  const auto [dropped200, dropped800] = first_sinkage(0.0);
  const double area = M_PI * (t.outer_radius * t.outer_radius - t.inner_radius * t.inner_radius);
  const double k = soil.Kc / t.outer_radius + soil.Kphi;  // b: the ring's convex hull is the disc of the outer radius
  auto bekker = [&](double load) { return std::pow(load / (area * k), 1.0 / soil.n); };
  INFO("200 N: ramped " << ramped200 << ", dropped " << dropped200 << ", Bekker " << bekker(200) << "; 800 N: ramped "
                        << ramped800 << ", dropped " << dropped800 << ", Bekker " << bekker(800));
  CHECK(rel(ramped200, bekker(200)) < 0.03);
  CHECK(rel(ramped800, bekker(800)) < 0.03);
  CHECK(dropped800 > 1.15 * bekker(800));
  // A ramp longer than the settling is refused, naming the key.
  t.load_ramp = 1.5;
  CHECK_THROWS_WITH(rigs::run_shear(site, t), Catch::Contains("load_ramp") && Catch::Contains("1.5"));
}

TEST_CASE("calibrating on SCM-rig curves recovers the SCM soil within 5 %", "[lowfi][scm][recovery]") {
  test::ScratchDir dir("scm_recovery");
  lowfi::ScmSoil soil = test::scm_dry_sand();
  soil.janosi_k = 0.02;
  // The plates are pushed without damping (R v would add 3 kPa at 0.1 m/s); the annulus settles with it.
  const auto site = test::scm_site(soil, 0.005, 1e-3);
  const auto damped = test::scm_site(soil, 0.005, 1e-3, {"damping"});
  std::vector<rigs::PlateRow> plate;
  for (double r : {0.1, 0.2}) {
    rigs::PlateTest t;
    t.radius = r;
    t.speed = 0.1;
    t.samples = 100;
    const auto rows = rigs::run_plate(site, t);
    plate.insert(plate.end(), rows.begin(), rows.end());
  }
  rigs::ShearTest s;
  s.loads = {200, 500, 800, 1100};
  s.settle_time = 2.0;
  s.max_angle = 1.0;
  s.samples = 50;
  const auto shear = rigs::run_shear(damped, s);
  rigs::write_plate_csv((dir.path / "plate.csv").string(), plate);
  rigs::write_shear_csv((dir.path / "shear.csv").string(), shear);
  const bayes::CalibrationProblem problem(bayes::load_plate_csv((dir.path / "plate.csv").string()),
                                          bayes::load_shear_csv((dir.path / "shear.csv").string()),
                                          bayes::default_priors());
  const bayes::PointEstimate est = bayes::estimate_point(problem, bayes::PointEstimateOptions{.seed = 3});
  const auto& p = est.map;
  INFO("Kc " << p[bayes::kKc] << ", Kphi " << p[bayes::kKphi] << ", n " << p[bayes::kN] << ", c " << p[bayes::kCohesion]
             << ", phi " << p[bayes::kFriction] << ", k " << p[bayes::kJanosi] << "\n"
             << est.ceres_report);
  for (double r : {0.1, 0.2}) CHECK(rel(p[bayes::kKc] / r + p[bayes::kKphi], soil.Kc / r + soil.Kphi) < 0.05);
  CHECK(rel(p[bayes::kN], soil.n) < 0.05);
  CHECK(rel(p[bayes::kFriction], soil.friction_deg) < 0.05);
  CHECK(rel(p[bayes::kJanosi], soil.janosi_k) < 0.05);
  CHECK(std::abs(p[bayes::kCohesion] - soil.cohesion) < 0.05 * soil.cohesion + 100);
  // The elastic stiffness comes from the unload-reload rows.
  INFO("Ke " << problem.elastic().ke << " +- " << problem.elastic().sd << " from " << problem.elastic().rows
             << " rows");
  REQUIRE(problem.elastic().fitted);
  CHECK(rel(problem.elastic().ke, soil.elastic_stiffness) < 0.05);
}
