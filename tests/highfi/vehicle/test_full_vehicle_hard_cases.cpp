// The full HMMWV's hard cases: dropped from 0.3 m, at rest under the Moon's gravity, braked fully from
// 10 m/s, at full lock at 4 m/s, and with a wheel jacked off the ground. Each stays finite and bounded
// with its joints held.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "highfi/multibody/mb_integrator.hpp"
#include "highfi/vehicle/vehicle_run.hpp"

using namespace terracal;
using namespace terracal::vehicle;

namespace {
struct Watch {
  double violation = 0, lowest = 1e9, highest = -1e9, max_speed = 0, max_roll = 0;
  bool finite = true;
  void look(const FullVehicle& v, const mb::MbIntegrator& in) {
    const mb::RigidBody& c = v.system().bodies[std::size_t(v.chassis())];
    for (const mb::RigidBody& b : v.system().bodies)
      finite = finite && b.position.allFinite() && b.velocity.allFinite() && b.omega.allFinite();
    violation = std::max(violation, in.constraint_violation());
    lowest = std::min(lowest, c.position.z());
    highest = std::max(highest, c.position.z());
    max_speed = std::max(max_speed, c.velocity.norm());
    const mb::Mat3 r = c.rotation();
    max_roll = std::max(max_roll, std::abs(std::atan2(r(2, 1), r(2, 2))));
  }
};

FullVehicleSpec hmmwv() { return load_full_vehicle("hmmwv"); }
double design_height(const FullVehicleSpec& s) { return s.tire.unloaded_radius + 0.026; }
}  // namespace

TEST_CASE("full vehicle, hard cases: a drop from 0.3 m lands and settles", "[vehicle]") {
  const FullVehicleSpec spec = hmmwv();
  FullVehicle v(spec, mb::Vec3(0, 0, design_height(spec) + 0.3));
  mb::MbIntegrator in(v.system(), {1e-5, 1e-7});
  Watch w;
  for (double t = 0.05; t <= 3 + 1e-9; t += 0.05) {
    in.advance(t);
    w.look(v, in);
  }
  const mb::RigidBody& c = v.system().bodies[std::size_t(v.chassis())];
  INFO("chassis between " << w.lowest << " and " << w.highest << " m, now " << c.position.z() << " m at "
                          << c.velocity.norm() << " m/s; constraint error " << w.violation);
  CHECK(w.finite);
  CHECK(w.lowest > 0.6);  // the chassis' centre never comes near the ground (it rides at 1.11 m)
  CHECK(c.velocity.norm() < 0.05);
  CHECK(w.violation < 1e-6);
  for (const auto& k : v.contacts()) CHECK(k.touching);
}

TEST_CASE("full vehicle, hard cases: at rest under the Moon's gravity", "[vehicle]") {
  const FullVehicleSpec spec = hmmwv();
  FullVehicle v(spec, mb::Vec3(0, 0, design_height(spec)));
  v.system().gravity = mb::Vec3(0, 0, -1.62);
  mb::MbIntegrator in(v.system(), {1e-6, 1e-8});
  Watch w;
  for (double t = 0.1; t <= 8 + 1e-9; t += 0.1) {
    in.advance(t);
    w.look(v, in);
  }
  double fz = 0;
  for (const auto& k : v.contacts()) fz += k.fz;
  const double weight = spec.total_mass() * 1.62;
  INFO("tire loads " << fz << " N against the weight " << weight << " N; chassis up to " << w.highest
                     << " m; constraint error " << w.violation);
  CHECK(w.finite);
  CHECK(std::abs(fz - weight) / weight < 1e-3);  // the springs lift it, but it stays on its wheels
  CHECK(w.violation < 1e-7);
}

TEST_CASE("full vehicle, hard cases: full braking from 10 m/s stops it straight", "[vehicle]") {
  const FullVehicleSpec spec = hmmwv();
  FullVehicle v(spec, mb::Vec3(0, 0, design_height(spec)));
  mb::MbIntegrator in(v.system(), {1e-5, 1e-7});
  in.advance(3.0);  // settled
  set_forward_speed(v, 10.0);
  v.set_driver([](double t) { return DriverInput{0, 0, t > 3.0 ? 1.0 : 0.0}; });
  in.reinitialize();
  Watch w;
  const mb::RigidBody& c = v.system().bodies[std::size_t(v.chassis())];
  const double x0 = c.position.x();
  for (double t = 3.05; t <= 7 + 1e-9; t += 0.05) {
    in.advance(t);
    w.look(v, in);
  }
  INFO("stopped after " << c.position.x() - x0 << " m, speed " << c.velocity.norm() << " m/s, drift y "
                        << c.position.y() << " m; constraint error " << w.violation);
  CHECK(w.finite);
  CHECK(c.velocity.norm() < 0.05);
  // Tires that can give ~0.8 g stop it in 10^2 / (2 * 0.8 g) = 6.4 m or more.
  CHECK(c.position.x() - x0 > 5.0);
  CHECK(c.position.x() - x0 < 15.0);
  CHECK(std::abs(c.position.y()) < 0.1);
  CHECK(w.violation < 1e-5);  // at rtol 1e-5
}

TEST_CASE("full vehicle, hard cases: full lock at 4 m/s", "[vehicle]") {
  const FullVehicleSpec spec = hmmwv();
  FullVehicle v(spec, mb::Vec3(0, 0, design_height(spec)));
  mb::MbIntegrator in(v.system(), {1e-6, 1e-8});
  in.advance(3.0);
  set_forward_speed(v, 4.0);
  v.set_driver([](double t) { return DriverInput{std::min(1.0, std::max(0.0, t - 3.0)), 0.1, 0}; });
  in.reinitialize();
  Watch w;
  for (double t = 3.05; t <= 9 + 1e-9; t += 0.05) {
    in.advance(t);
    if (v.update_gear()) in.reinitialize();
    w.look(v, in);
  }
  const mb::RigidBody& c = v.system().bodies[std::size_t(v.chassis())];
  const mb::Vec3 yaw_rate = c.rotation() * c.omega;
  INFO("yaw rate " << yaw_rate.z() << " rad/s at " << c.velocity.norm() << " m/s; largest roll " << w.max_roll
                   << " rad; chassis between " << w.lowest << " and " << w.highest << " m; constraint error "
                   << w.violation);
  CHECK(w.finite);
  CHECK(yaw_rate.z() > 0.3);  // turning left, tightly
  CHECK(w.max_roll < 0.2);    // on its wheels
  CHECK(w.max_speed < 10.0);  // bounded
  CHECK(w.violation < 1e-6);
}

TEST_CASE("full vehicle, hard cases: a wheel off the ground spins up alone through the open differentials",
          "[vehicle]") {
  const FullVehicleSpec spec = hmmwv();
  FullVehicle v(spec, mb::Vec3(0, 0, design_height(spec)));
  mb::MbSystem& s = v.system();
  // A jack under the front left wheel lifts it from 3 s on: its force grows over 0.5 s to 1.5 times
  // the wheel's static load; from 4 s the driver holds half throttle.
  const int lifted = v.corners()[0].spindle;
  const double jack = 1.5 * spec.total_mass() * 9.81 / 4;
  s.external.push_back({[=](double t, const std::vector<mb::RigidBody>&, std::vector<mb::Wrench>& w) {
                          w[std::size_t(lifted)].force.z() += jack * std::clamp((t - 3.0) / 0.5, 0.0, 1.0);
                        },
                        {lifted}});
  v.set_driver([](double t) { return DriverInput{0, t > 4.0 ? 0.5 : 0.0, 0}; });
  mb::MbIntegrator in(s, {1e-6, 1e-8});
  Watch w;
  in.advance(3.0);
  const double x0 = s.bodies[std::size_t(v.chassis())].position.x();
  for (double t = 3.05; t <= 8 + 1e-9; t += 0.05) {
    in.advance(t);
    if (v.update_gear()) in.reinitialize();
    w.look(v, in);
  }
  const auto contacts = v.contacts();
  const auto spin = [&](int k) {
    const mb::RigidBody& b = s.bodies[std::size_t(v.corners()[std::size_t(k)].spindle)];
    return std::abs(b.omega.y());
  };
  const double moved = s.bodies[std::size_t(v.chassis())].position.x() - x0;
  INFO("lifted wheel: load " << contacts[0].fz << " N, spin " << spin(0) << " rad/s; others' spin " << spin(1) << ", "
                             << spin(2) << ", " << spin(3) << " rad/s; chassis moved " << moved
                             << " m; constraint error " << w.violation);
  CHECK(w.finite);
  CHECK_FALSE(contacts[0].touching);
  CHECK(contacts[1].touching);
  // Open centre and axle differentials give every wheel the torque the free one takes (the torque that
  // spins up its 6.8 kg m^2): it races, and the three on the ground roll alike, slowly.
  CHECK(spin(0) > 10 * spin(1));
  CHECK(std::abs(spin(2) - spin(3)) < 0.05 * spin(2));
  CHECK(std::abs(spin(1) - spin(2)) < 0.1 * spin(2));
  CHECK(moved > 0);
  CHECK(w.max_speed < 5.0);
  CHECK(w.max_roll < 0.2);
  CHECK(w.violation < 1e-5);  // at rtol 1e-6, the free wheel at 134 rad/s
}
