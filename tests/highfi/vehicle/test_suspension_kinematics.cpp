// The double-wishbone template: its kinematics from the hardpoints (camber and toe against travel)
// agree with the dynamic model driven slowly through the same travel by a post under the wheel, on
// both sides, and the HMMWV front's curves have the shape its geometry implies.
#include <catch2/catch.hpp>

#include <cmath>

#include "highfi/multibody/mb_integrator.hpp"
#include "highfi/vehicle/suspension_kinematics.hpp"
#include "tests/highfi/vehicle/hmmwv_front_suspension.hpp"

using namespace terracal;
using namespace terracal::vehicle;

namespace {
DoubleWishboneSpec hmmwv_front() {
  const nlohmann::json j = test::hmmwv_front_suspension_json();
  return read_double_wishbone(JsonObject(j, "test", ""));
}
}  // namespace

TEST_CASE("suspension: the HMMWV front's camber and toe against travel", "[vehicle]") {
  const DoubleWishboneSpec spec = hmmwv_front();
  const std::vector<double> travels{-0.1, -0.05, 0.0, 0.05, 0.1};
  const auto left = double_wishbone_kinematics(spec, travels, 1), right = double_wishbone_kinematics(spec, travels, -1);
  for (std::size_t k = 0; k < travels.size(); ++k) {
    INFO("travel " << travels[k] << ": camber " << left[k].camber * 180 / M_PI << " deg, toe "
                   << left[k].toe * 180 / M_PI << " deg, lateral " << left[k].lateral << " m");
    CHECK(std::abs(left[k].travel - travels[k]) < 1e-10);
    // The right side is the mirror image.
    CHECK(std::abs(left[k].camber - right[k].camber) < 1e-10);
    CHECK(std::abs(left[k].toe - right[k].toe) < 1e-10);
  }
  // At the design position the spindle's axis is lateral: no camber, no toe.
  CHECK(std::abs(left[2].camber) < 1e-10);
  CHECK(std::abs(left[2].toe) < 1e-10);
  // Upper arm shorter than the lower one: camber turns negative in bump (the top comes in).
  CHECK(left[4].camber < -0.005);
  CHECK(left[3].camber < 0);
}

TEST_CASE("suspension: the dynamic model held quasi-statically follows the kinematic solve", "[vehicle]") {
  const DoubleWishboneSpec spec = hmmwv_front();
  for (double side : {1.0, -1.0}) {
    mb::MbSystem s;
    mb::RigidBody chassis;
    chassis.fixed = true;
    const int c = s.add_body(chassis);
    const WishboneSide w = build_double_wishbone(s, spec, c, c, mb::Vec3::Zero(), mb::Vec3::Zero(), side);
    const double z0 = s.bodies[std::size_t(w.spindle)].position.z();
    // A post under the wheel (a stiff spring to a target height) sweeps the travel from -0.08 to
    // +0.08 m over 8 s, as a suspension test rig does.
    const auto target = [z0](double t) { return z0 - 0.08 + 0.02 * t; };
    s.external.push_back([&, target](double t, const std::vector<mb::RigidBody>& b, std::vector<mb::Wrench>& f) {
      const mb::RigidBody& sp = b[std::size_t(w.spindle)];
      f[std::size_t(w.spindle)].force.z() += 2e7 * (target(t) - sp.position.z()) - 2e4 * (sp.velocity.z() - 0.02);
    });
    s.bodies[std::size_t(w.spindle)].position.z() = target(0);  // the assembly moves the rest onto it
    mb::MbIntegrator in(s, {1e-8, 1e-10});
    std::vector<double> travels;
    std::vector<WheelAlignment> dynamic;
    for (double t = 0.5; t <= 8.0 + 1e-9; t += 0.5) {
      in.advance(t);
      const mb::RigidBody& sp = s.bodies[std::size_t(w.spindle)];
      WheelAlignment a = alignment(sp.rotation() * mb::Vec3::UnitY(), side);
      a.travel = sp.position.z() - z0;
      travels.push_back(a.travel);
      dynamic.push_back(a);
    }
    const auto kinematic = double_wishbone_kinematics(spec, travels, side);
    double worst = 0, span = 0;
    for (std::size_t k = 0; k < travels.size(); ++k) {
      worst = std::max(
          {worst, std::abs(dynamic[k].camber - kinematic[k].camber), std::abs(dynamic[k].toe - kinematic[k].toe)});
      span = std::max(span, std::abs(dynamic[k].camber - dynamic[0].camber));
    }
    INFO("side " << side << ": travel " << travels.front() << " .. " << travels.back() << " m; camber changes by "
                 << span << " rad; largest camber or toe difference " << worst << " rad");
    CHECK(travels.front() < -0.06);
    CHECK(travels.back() > 0.07);
    CHECK(span > 0.01);
    CHECK(worst < 1e-7);
  }
}
