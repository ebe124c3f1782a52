// The full vehicle (the HMMWV preset) at rest on flat rigid ground: the tires carry its weight, the
// loads balance its moments, and once settled it stays where it is for 60 s with its joints closed.
#include <catch2/catch.hpp>

#include <cmath>

#include "highfi/multibody/mb_integrator.hpp"
#include "highfi/vehicle/full_vehicle.hpp"

using namespace terracal;
using namespace terracal::vehicle;

TEST_CASE("full vehicle: the HMMWV at rest on rigid ground carries its weight and stays still for 60 s", "[vehicle]") {
  const FullVehicleSpec spec = load_full_vehicle("hmmwv");
  // Dropped with the wheels touching the ground at the design position; the springs lift it to its
  // ride height.
  FullVehicle v(spec, mb::Vec3(0, 0, spec.tire.unloaded_radius + 0.026));
  mb::MbSystem& s = v.system();
  mb::MbIntegrator in(s, {1e-6, 1e-8});
  const double weight = spec.total_mass() * 9.81;
  // It settles within 30 s: at standstill the steady-slip tires hold it by slip damping only (the
  // vehicle has no brakes yet), so the settling's last millimetres creep out slowly.
  in.advance(30.0);
  const mb::Vec3 start = s.bodies[std::size_t(v.chassis())].position;
  double worst_sum = 0, worst_moment = 0, worst_violation = 0, worst_side = 0;
  for (double t = 30.5; t <= 90 + 1e-9; t += 0.5) {
    in.advance(t);
    const auto c = v.contacts();
    double fz = 0, moment_x = 0, moment_y = 0, first_x = 0, first_y = 0;
    for (const auto& k : c) fz += k.fz, moment_x += k.fz * k.point.x(), moment_y += k.fz * k.point.y();
    // The vehicle's centre of mass: the tires' loads must have it as their centre.
    double mass = 0;
    for (const auto& b : s.bodies)
      mass += b.mass, first_x += b.mass * b.position.x(), first_y += b.mass * b.position.y();
    worst_sum = std::max(worst_sum, std::abs(fz - weight) / weight);
    worst_moment =
        std::max({worst_moment, std::abs(moment_x / fz - first_x / mass), std::abs(moment_y / fz - first_y / mass)});
    worst_side = std::max({worst_side, std::abs(c[0].fz - c[1].fz) / c[0].fz, std::abs(c[2].fz - c[3].fz) / c[2].fz});
    worst_violation = std::max(worst_violation, in.constraint_violation());
  }
  const mb::RigidBody& chassis = s.bodies[std::size_t(v.chassis())];
  const auto c = v.contacts();
  INFO("wheel loads " << c[0].fz << ", " << c[1].fz << ", " << c[2].fz << ", " << c[3].fz << " N; weight " << weight
                      << " N; largest relative error of the sum " << worst_sum
                      << "; centre of the loads off the centre of mass by " << worst_moment << " m; left/right "
                      << worst_side << "; chassis moved " << (chassis.position - start).norm()
                      << " m over 60 s, speed now " << chassis.velocity.norm() << " m/s; constraint error "
                      << worst_violation << "; " << in.stats().steps << " steps");
  CHECK(worst_sum < 1e-3);
  CHECK(worst_moment < 1e-3);
  CHECK(worst_side < 2e-3);  // the steering's Pitman arm (2.3 kg) sits on the left
  CHECK((chassis.position - start).head<2>().norm() < 1e-3);
  CHECK(chassis.velocity.norm() < 1e-4);
  CHECK(chassis.omega.norm() < 1e-4);
  CHECK(worst_violation < 1e-8);
  for (const auto& k : c) CHECK(k.touching);
}

TEST_CASE("full vehicle: bad vehicle files are refused with the key named", "[vehicle][bad_input]") {
  nlohmann::json j = nlohmann::json::parse(full_vehicle_preset_json("hmmwv"));
  j["chassis"]["mass"] = 0;
  CHECK_THROWS_WITH(read_full_vehicle(j, "v.json"), Catch::Contains("chassis.mass") && Catch::Contains("v.json"));
  j = nlohmann::json::parse(full_vehicle_preset_json("hmmwv"));
  j["axles"][1]["suspension"]["shock"]["damping"] = -5;
  CHECK_THROWS_WITH(read_full_vehicle(j, "v.json"), Catch::Contains("axles[1].suspension.shock.damping"));
  j = nlohmann::json::parse(full_vehicle_preset_json("hmmwv"));
  j["axles"] = nlohmann::json::array();
  CHECK_THROWS_WITH(read_full_vehicle(j, "v.json"), Catch::Contains("axles"));
  j = nlohmann::json::parse(full_vehicle_preset_json("hmmwv"));
  j["whee1"] = 3;
  CHECK_THROWS_WITH(read_full_vehicle(j, "v.json"), Catch::Contains("whee1"));
  CHECK_THROWS_WITH(load_full_vehicle("no_such_vehicle.json"), Catch::Contains("no_such_vehicle.json"));
}
