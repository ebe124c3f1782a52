// Slip sinkage (lowfi/slip_sinkage.hpp): Lyasko's relation, the slip a surface point sees, and the
// two models that use it: Wong-Reece (from the wheel's slip) and the SCM effect slip_sinkage (per
// node). With the effect a driven wheel sinks by Lyasko's ratio; a plate, which does not slip, and
// every run without the effect see Bekker's law unchanged.
#include <catch2/catch.hpp>

#include <cmath>

#include "core/errors.hpp"
#include "lowfi/slip_sinkage.hpp"
#include "lowfi/wong_reece.hpp"
#include "scm_test_soils.hpp"
#include "virtual_bevameter/plate_rig.hpp"
#include "virtual_bevameter/wheel_rig.hpp"

using namespace terracal;
using Catch::Matchers::Contains;

TEST_CASE("slip sinkage: Lyasko's relation and the slip a surface point sees", "[lowfi][slip_sinkage]") {
  const lowfi::SlipSinkage lyasko;  // S = 1.5: z / z0 = (1 + i) / (1 - 0.5 i)
  for (double i : {0.0, 0.2, 0.5, 0.8, 1.0})
    CHECK(lowfi::slip_sinkage_ratio(lyasko, i) == Approx((1 + i) / (1 - 0.5 * i)).epsilon(1e-14));
  CHECK(lowfi::slip_sinkage_ratio(lyasko, -0.5) == 1.0);  // a skid gets none
  CHECK(lowfi::slip_sinkage_ratio({3.0}, 0.8) == Approx(5.0));
  // The stretch of p = k (z / f)^n that makes Bekker's static wheel (W ~ k z^((2n+1)/2)) sink F times deeper.
  const double n = 1.1, F = lowfi::slip_sinkage_ratio(lyasko, 0.5);
  CHECK(std::pow(lowfi::pressure_sinkage_stretch(lyasko, 0.5, n), 2 * n / (2 * n + 1)) == Approx(F).epsilon(1e-14));

  // A wheel of radius 0.5 m turning at 2 rad/s and travelling at 0.6 m/s: slip 0.4 at the bottom of
  // its rim, 1 - 0.6 cos(theta) / 1 on the arc; a plate pressed straight down: no slip.
  const double r = 0.5, w = 2, v = 0.6;
  for (double th : {0.0, 0.3}) {
    const Vec3<double> nrm{-std::sin(th), 0, std::cos(th)};  // the soil's outward normal at the contact
    const Vec3<double> rim{r * std::sin(th), 0, -r * std::cos(th)};
    const Vec3<double> omega{0, w, 0}, u{v, 0, 0};
    CHECK(lowfi::surface_slip(u + cross(omega, rim), u, nrm) == Approx(1 - v * std::cos(th) / (w * r)).epsilon(1e-12));
  }
  CHECK(lowfi::surface_slip({0, 0, -0.05}, {0, 0, -0.05}, {0, 0, 1}) == 0.0);
  CHECK(lowfi::surface_slip({1.2, 0, 0}, {2.0, 0, 0}, {0, 0, 1}) == 0.0);  // the rim lags the travel: a skid
}

TEST_CASE("slip sinkage: the block 'Slip sinkage' is read and checked", "[lowfi][slip_sinkage]") {
  CHECK(lowfi::parse_slip_sinkage(nlohmann::json::parse(R"({"Model": "Lyasko", "S": 3})"), "f").S == 3.0);
  CHECK(lowfi::parse_slip_sinkage(nlohmann::json::parse("{}"), "f").S == 1.5);
  CHECK_THROWS_WITH(lowfi::parse_slip_sinkage(nlohmann::json::parse(R"({"S": -1})"), "f.json"),
                    Contains("f.json: key 'Slip sinkage.S' = -1: expected in [0, 20]"));
  CHECK_THROWS_WITH(lowfi::parse_slip_sinkage(nlohmann::json::parse(R"({"Model": "Ding"})"), "f.json"),
                    Contains("key 'Slip sinkage.Model'") && Contains("Ding"));
  CHECK_THROWS_WITH(lowfi::parse_slip_sinkage(nlohmann::json::parse(R"({"s": 2})"), "f.json"),
                    Contains("unknown key 'Slip sinkage.s'"));
}

// Wong-Reece carries the load on the stretched law: a driven wheel sinks Lyasko's ratio deeper than
// without slip sinkage, to within what cohesion and the shear's vertical part (which the stretch
// does not scale) leave; off, the model as published.
TEST_CASE("slip sinkage: Wong-Reece's wheel sinks by Lyasko's ratio", "[lowfi][slip_sinkage][wong_reece]") {
  const lowfi::ScmSoil soil = test::scm_dry_sand();
  const lowfi::WongReeceWheel wheel{0.47, 0.25};
  lowfi::WongReeceOptions on;
  on.slip_sinkage = true;
  const double load = 108 * 9.81;
  for (double i : {0.0, 0.1, 0.3, 0.5, 0.7}) {
    const auto off_r = lowfi::wong_reece(soil, wheel, load, i, {});
    const auto on_r = lowfi::wong_reece(soil, wheel, load, i, on);
    const double expected = lowfi::slip_sinkage_ratio(soil.slip_sinkage, i);
    INFO("slip " << i << ": sinkage " << off_r.sinkage << " -> " << on_r.sinkage << " m, ratio "
                 << on_r.sinkage / off_r.sinkage << " against Lyasko's " << expected);
    CHECK(on_r.sinkage / off_r.sinkage == Approx(expected).epsilon(0.03));
    CHECK(on_r.vertical_force == Approx(load).epsilon(1e-6));
  }
}

// The SCM wheel with the effect: its sinkage grows with slip by Lyasko's ratio over the wheel
// without it; a plate (pressed straight down: no slip under it) gives the same curve to the last digit.
TEST_CASE("slip sinkage: SCM's driven wheel sinks by Lyasko's ratio, a plate does not move",
          "[lowfi][scm][slip_sinkage]") {
  const lowfi::ScmSoil soil = test::scm_dry_sand();
  const auto off = test::scm_site(soil, 0.01, 1e-3, {"damping"});
  const auto on = test::scm_site(soil, 0.01, 1e-3, {"damping", "slip_sinkage"});
  rigs::WheelRun run;
  run.duration = 4;
  for (double i : {0.2, 0.5, 0.7}) {
    const auto a = rigs::run_wheel(off, rigs::WheelSpec{}, i, run);
    const auto b = rigs::run_wheel(on, rigs::WheelSpec{}, i, run);
    const double expected = lowfi::slip_sinkage_ratio(soil.slip_sinkage, i);
    INFO("slip " << i << ": sinkage " << a.sinkage << " -> " << b.sinkage << " m, ratio " << b.sinkage / a.sinkage
                 << " against Lyasko's " << expected << "; DBP " << a.dbp << " -> " << b.dbp << " N");
    CHECK(b.sinkage / a.sinkage == Approx(expected).epsilon(0.1));
    // Deeper, so more compaction resistance: at high slip it outweighs the longer contact's shear
    // (DBP -13 % at 0.5, -18 % at 0.7; +1.6 % at 0.2).
    if (i >= 0.5) CHECK(b.dbp < 0.95 * a.dbp);
    CHECK(rigs::unsteady_reason(b).empty());
  }
  const rigs::PlateTest plate;
  const auto pa = rigs::run_plate(off, plate), pb = rigs::run_plate(on, plate);
  REQUIRE(pa.size() == pb.size());
  for (std::size_t k = 0; k < pa.size(); ++k) {
    CHECK(pa[k].sinkage == pb[k].sinkage);
    CHECK(pa[k].force == pb[k].force);
  }
}
