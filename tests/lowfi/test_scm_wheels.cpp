// The SCM soil under wheels driven from outside (lowfi/scm_wheels.hpp), as the full vehicle's explicit
// co-simulation drives it: the test integrates the wheel itself, holding each SCM step's wrench over
// the step, and the wheel sinks and pulls as the single-wheel rig's does on the same soil.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "core/errors.hpp"
#include "lowfi/scm_wheels.hpp"
#include "lowfi/wong_reece.hpp"
#include "scm_test_soils.hpp"
#include "virtual_bevameter/wheel_rig.hpp"

using namespace terracal;
using Catch::Matchers::Contains;

namespace {
constexpr double kG = 9.81;

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }

bool zero(const BodyWrench& f) {
  for (int q = 0; q < 3; ++q)
    if (f.force[q] != 0 || f.torque[q] != 0) return false;
  return true;
}

lowfi::ScmSettings damped(double grid) {
  lowfi::ScmSettings s;
  s.grid = grid;
  s.time_step = 1e-3;
  s.effects.enable<lowfi::ScmDamping>();
  return s;
}

lowfi::ScmWheelShape shape_of(const rigs::WheelSpec& w) {
  return {"test wheel", w.radius, w.width, w.grouser_count, w.grouser_height, w.grouser_thickness};
}

rigs::WheelRun run_of(double duration) {
  rigs::WheelRun r;
  r.duration = duration;
  r.average_from = 0.5;
  return r;
}

// Means over the second half of a run of the wheel driven below.
struct DrivenRun {
  double sinkage = 0;          // geometric, as the rig measures it: the lowest rim point below the surface
  double adapter_sinkage = 0;  // ScmWheels::sinkage
  double vertical = 0, dbp = 0, torque = 0, area = 0;
  bool finite = true;
};

// The rig's wheel with the rig's motion (carriage at omega r (1 - s) along +x, spin omega about +y,
// started touching the surface, at rest, under its whole weight at once), but moved by the test: a
// 1-DOF vertical body under gravity and the adapter's vertical force, which is held over each SCM step
// and integrated in `substeps` semi-implicit Euler substeps, as a variable-step integrator would
// integrate a held force. The pose and spin angle advance exactly.
DrivenRun drive(const lowfi::ScmSoil& soil, const lowfi::ScmSettings& settings, const rigs::WheelSpec& w, double slip,
                double duration, int substeps) {
  lowfi::ScmWheels wheels(soil, settings, {shape_of(w)});
  const double dt = settings.time_step, h = dt / substeps;
  const double outer = w.radius + w.grouser_height;
  const double speed = w.angular_velocity * w.radius * (1 - slip);
  BodyState s;
  s.position = {-0.5 * speed * duration, 0, settings.surface_height + outer};
  s.velocity = {speed, 0, 0};
  s.omega = {0, w.angular_velocity, 0};
  const long steps = long(std::ceil(duration / dt - 1e-9));
  DrivenRun r;
  long n = 0;
  for (long k = 1; k <= steps; ++k) {
    wheels.step({s});
    const BodyWrench& f = wheels.wrenches()[0];
    for (int i = 0; i < substeps; ++i) {
      s.velocity.z += h * (f.force.z / w.mass - kG);
      s.position.z += h * s.velocity.z;
    }
    s.position.x += dt * speed;
    s.orientation = integrate_rotation(s.orientation, s.omega, dt);
    r.finite = r.finite && std::isfinite(f.force.x) && std::isfinite(f.force.z) && std::isfinite(f.torque.y) &&
               std::isfinite(s.position.z);
    if (2 * k <= steps) continue;
    ++n;
    // The wrench of this step belongs to the pose the step was given: the sinkage is measured there.
    r.sinkage += settings.surface_height - (wheels.terrain().bodies()[0].position.z - outer);
    r.adapter_sinkage += wheels.sinkage(0);
    r.vertical += f.force.z;
    r.dbp += f.force.x;
    r.torque += -f.torque.y;
    r.area += wheels.contact_area(0);
  }
  for (double* x : {&r.sinkage, &r.adapter_sinkage, &r.vertical, &r.dbp, &r.torque, &r.area}) *x /= double(n);
  return r;
}
}  // namespace

// (a) Static sinkage. The rig's standstill wheel sinks with its whole weight put on at once: it
// overshoots, the soil yields to the deepest point, and it settles back elastically. The test's own
// integration of the held wrench (10 substeps per SCM step) is not the terrain's symplectic Euler,
// so the two are independent integrations of the same wheel: 0.0288 m against the rig's 0.0279 m
// (+3.2 %; the sudden load's overshoot, integrated within the step, yields the soil a little deeper).
// With one substep the test's integration is the terrain's own and the two agree to every digit.
TEST_CASE("SCM wheels driven from outside: a wheel under its weight settles at the rig's static sinkage",
          "[lowfi][scm][wheels]") {
  const lowfi::ScmSoil soil = test::scm_dry_sand();
  const lowfi::ScmSettings settings = damped(0.01);
  rigs::WheelSpec w;  // r 0.47 m, b 0.25 m, 108 kg
  w.angular_velocity = 0;
  const auto rig = rigs::run_wheel(lowfi::ScmSite(soil, settings), w, 0.0, run_of(4.0));
  const DrivenRun a = drive(soil, settings, w, 0.0, 4.0, 10);
  const double load = w.mass * kG;
  INFO("static sinkage: adapter " << a.sinkage << " m (its nodes " << a.adapter_sinkage << " m), rig " << rig.sinkage
                                  << " m; vertical force " << a.vertical << " N against " << load << " N; area "
                                  << a.area << " m^2");
  REQUIRE(a.finite);
  CHECK(rel(a.sinkage, rig.sinkage) < 0.05);
  CHECK(rel(a.vertical, load) < 0.01);
  // The node under the axle lies under the lowest rim point: the adapter's sinkage is the rig's measure.
  CHECK(std::abs(a.adapter_sinkage - a.sinkage) < 1e-9);
  CHECK(a.sinkage > 0.005);  // a real sinkage, not a wheel resting on the surface
  CHECK(std::abs(a.dbp) < 1e-6 * load);
}

// (b) A driven wheel at slip 0.3: the soil pushes it forward. Its traction is the Janosi shear of
// SCM's nodes: the rigid-wheel integral of the same assumptions (Wong-Reece with the peak stress at
// the bottom and the shear counted per ground point, lowfi/wong_reece.hpp) predicts its torque and
// pull: the torque within 0.1 %, the pull within 7 % (damping and the rear's elastic rebound, which
// the integral leaves out, cost compaction resistance), and the rig's wheel within 0.01 %.
TEST_CASE("SCM wheels driven from outside: a wheel spinning faster than it moves gets the Janosi drawbar pull",
          "[lowfi][scm][wheels]") {
  const lowfi::ScmSoil soil = test::scm_dry_sand();
  const lowfi::ScmSettings settings = damped(0.01);
  const rigs::WheelSpec w;  // 1 rad/s
  const double slip = 0.3, load = w.mass * kG;
  const DrivenRun a = drive(soil, settings, w, slip, 4.0, 10);
  const auto rig = rigs::run_wheel(lowfi::ScmSite(soil, settings), w, slip, run_of(4.0));
  lowfi::WongReeceOptions scm_like;
  scm_like.c1 = scm_like.c2 = 0;
  scm_like.shear_displacement = lowfi::ShearDisplacement::ground;
  const auto janosi = lowfi::wong_reece(soil, {w.radius, w.width}, load, slip, scm_like);
  const double mohr = soil.cohesion * a.area + load * std::tan(soil.friction_deg * M_PI / 180);
  INFO("slip " << slip << ": DBP adapter " << a.dbp << " N, rig " << rig.dbp << " N, Janosi integral " << janosi.dbp
               << " N; torque adapter " << a.torque << " N m, rig " << rig.torque << " N m, integral " << janosi.torque
               << " N m; sinkage adapter " << a.sinkage << " m, rig " << rig.sinkage << " m, integral "
               << janosi.sinkage << " m; Mohr-Coulomb bound " << mohr << " N");
  REQUIRE(a.finite);
  CHECK(a.dbp > 0.1 * load);  // forward, and a real pull
  CHECK(a.torque > 0);        // the soil resists the spin: the drive must supply torque
  CHECK(rel(a.dbp, rig.dbp) < 0.02);
  CHECK(rel(a.torque, rig.torque) < 0.01);
  CHECK(rel(a.dbp, janosi.dbp) < 0.12);
  CHECK(rel(a.torque, janosi.torque) < 0.03);
  CHECK(a.torque / w.radius < mohr);  // the shear cannot exceed the soil's strength over the contact
  CHECK(rel(a.vertical, load) < 0.02);
}

// The adapter is the terrain's own contact: fed the states the terrain's symplectic Euler produces
// for the rig's grousered wheel, it gives the same wrenches to rounding.
TEST_CASE("SCM wheels driven from outside: a grousered wheel fed the terrain's own states gets its wrenches",
          "[lowfi][scm][wheels]") {
  const lowfi::ScmSoil soil = test::scm_dry_sand();
  const lowfi::ScmSettings settings = damped(0.02);
  rigs::WheelSpec w;
  w.grouser_count = 12;
  w.grouser_height = 0.03;
  w.grouser_thickness = 0.02;
  RigidBody b;
  b.name = "rig wheel";
  b.shape = wheel_shape(w.radius, w.width, w.grouser_count, w.grouser_height, w.grouser_thickness);
  b.position = {0, 0, w.radius + w.grouser_height};
  b.mass = w.mass;
  b.inertia = {10, 10, 10};
  b.motion.free = {false, false, true, false, false, false};
  b.motion.linear_velocity = {0.5 * w.radius, 0, 0};  // slip 0.5
  b.motion.angular_velocity = {0, 1, 0};
  lowfi::ScmTerrain own(soil, settings, {b});
  lowfi::ScmWheels wheels(soil, settings, {shape_of(w)});
  double worst = 0, peak_pull = 0;
  for (int k = 0; k < 1500; ++k) {
    own.step();
    wheels.step(own.bodies());
    const BodyWrench &x = own.wrenches()[0], &y = wheels.wrenches()[0];
    worst = std::max({worst, norm(x.force - y.force), norm(x.torque - y.torque)});
    peak_pull = std::max(peak_pull, x.force.x);
    REQUIRE(wheels.sinkage(0) == own.last_step().body_max_sinkage[0]);
  }
  INFO("largest wrench difference " << worst << " (N, N m); peak pull " << peak_pull << " N");
  CHECK(worst <= 1e-9 * w.mass * kG);
  CHECK(peak_pull > 0.1 * w.mass * kG);  // the grousers bite: a contact worth comparing
  CHECK(wheels.time() == own.time());
}

// (c) What the vehicle may hand over when things go wrong, and a wheel in the air.
TEST_CASE("SCM wheels driven from outside: a wheel in the air feels nothing; bad states are refused by name",
          "[lowfi][scm][wheels][hard]") {
  const lowfi::ScmSoil soil = test::scm_dry_sand();
  const rigs::WheelSpec w;
  auto front = shape_of(w), rear = shape_of(w);
  front.name = "front left";
  rear.name = "rear left";
  lowfi::ScmWheels wheels(soil, damped(0.02), {front, rear});
  REQUIRE(wheels.size() == 2);
  // Before the first step, and for wheels far above the soil: exactly zero, no contact.
  for (const auto& f : wheels.wrenches()) CHECK(zero(f));
  BodyState air, ground;
  air.position = {0, 0, 100};
  air.velocity = {30, -2, -50};
  air.omega = {1, 60, 3};
  ground.position = {3, 0, w.radius - 0.02};  // 2 cm into the soil
  ground.velocity = {1, 0, 0};
  ground.omega = {0, 1 / w.radius, 0};
  wheels.step({air, ground});
  CHECK(zero(wheels.wrenches()[0]));
  CHECK(wheels.sinkage(0) == 0);
  CHECK(wheels.contact_area(0) == 0);
  CHECK(wheels.wrenches()[1].force.z > 0);
  CHECK(std::abs(wheels.sinkage(1) - 0.02) < 1e-9);
  const double t = wheels.time();
  const std::size_t stored = wheels.terrain().stored_nodes();
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();

  auto refused = [&](BodyState bad, const char* what) {
    INFO(what);
    CHECK_THROWS_AS(wheels.step({ground, bad}), RunError);
    CHECK_THROWS_WITH(wheels.step({ground, bad}), Contains("rear left") && Contains(what));
  };
  BodyState s = ground;
  s.position.z = nan;
  refused(s, "position");
  s = ground;
  s.velocity.x = inf;
  refused(s, "velocity");
  s = ground;
  s.omega.y = nan;
  refused(s, "angular velocity");
  s = ground;
  s.orientation = {0, 0, 0, 0};
  refused(s, "orientation");
  s = ground;
  s.orientation.x = nan;
  refused(s, "orientation");
  s = ground;
  s.position.x = 1e12;  // past the grid's integer node range at 0.02 m
  refused(s, "beyond the grid's range");
  CHECK_THROWS_WITH(wheels.step({ground}), Contains("1 body states given for 2 bodies"));
  // Nothing of a refused step reached the soil.
  CHECK(wheels.time() == t);
  CHECK(wheels.terrain().stored_nodes() == stored);

  // A quaternion off unit length (as an integrator's drift leaves it) is the same rotation.
  lowfi::ScmWheels unit(soil, damped(0.02), {front}), scaled(soil, damped(0.02), {front});
  BodyState tilted = ground;
  tilted.orientation = Quat::from_axis_angle({1, 0, 0}, 0.2);
  unit.step({tilted});
  tilted.orientation = {2 * tilted.orientation.w, 2 * tilted.orientation.x, 2 * tilted.orientation.y,
                        2 * tilted.orientation.z};
  scaled.step({tilted});
  CHECK(norm(unit.wrenches()[0].force - scaled.wrenches()[0].force) < 1e-9 * norm(unit.wrenches()[0].force));
  CHECK(unit.wrenches()[0].force.z > 0);
  for (const auto& f : unit.wrenches())
    CHECK((std::isfinite(f.force.x) && std::isfinite(f.force.y) && std::isfinite(f.force.z)));

  // Bad shapes are bad input, named.
  auto bad = front;
  bad.radius = 0;
  CHECK_THROWS_AS(lowfi::ScmWheels(soil, damped(0.02), {bad}), InputError);
  CHECK_THROWS_WITH(lowfi::ScmWheels(soil, damped(0.02), {bad}), Contains("front left") && Contains("radius"));
  bad = front;
  bad.grouser_count = 10;
  CHECK_THROWS_WITH(lowfi::ScmWheels(soil, damped(0.02), {bad}), Contains("grouser_height > 0"));
}
