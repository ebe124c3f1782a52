// The 24-DOF model's vertical dynamics: the static state is an equilibrium, a dropped vehicle's
// wheels leave the ground and it settles back to the static heights, and braking pitches the nose
// down and accelerating pitches it up.
#include <cmath>

#include <catch2/catch.hpp>

#include "rom/half_implicit.hpp"
#include "rom/rom24.hpp"
#include "tests/rom/rom_test_vehicles.hpp"

using namespace terracal;
using namespace terracal::rom;
using namespace terracal::rom::testing;

TEST_CASE("rom 24-DOF: the static state is an equilibrium", "[rom]") {
  for (const char* name : {"hmmwv", "sedan"}) {
    const RomVehicle v = load_rom_vehicle(name);
    double y[Rom24::kStates], dy[Rom24::kStates];
    const int gear = Rom24::initial_state(v, 0.0, y);
    RomAux aux;
    Rom24::rhs(v, DriverInput{}, gear, y, dy, &aux, true);
    for (int i = 0; i < Rom24::kStates; ++i) {
      INFO(name << " state " << i);
      CHECK(std::fabs(dy[i]) < 1e-9);
    }
    const double weight = v.total_mass() * v.gravity;
    CHECK(aux.fz[0] + aux.fz[1] + aux.fz[2] + aux.fz[3] == Approx(weight).epsilon(1e-12));
  }
}

TEST_CASE("rom 24-DOF: dropped from 0.15 m the wheels leave the ground, land and settle", "[rom][hard]") {
  const RomVehicle v = hmmwv();
  double y[Rom24::kStates], y0[Rom24::kStates];
  int gear = Rom24::initial_state(v, 0.0, y);
  std::copy(y, y + Rom24::kStates, y0);
  y[Rom24::kZ] += 0.15;
  for (int w = 0; w < 4; ++w) y[Rom24::kWheelZ + w] += 0.15;
  RomAux aux;
  bool airborne = false;
  double lowest = 1e9;
  for (int k = 0; k < 5000; ++k) {
    REQUIRE(half_implicit_step<Rom24>(v, DriverInput{}, gear, y, 1e-3, &aux));
    if (aux.fz[0] == 0 && aux.fz[3] == 0) airborne = true;
    lowest = std::min(lowest, y[Rom24::kZ]);
  }
  CHECK(airborne);
  CHECK(lowest < y0[Rom24::kZ]);  // the landing compresses the springs below the static height
  CHECK(y[Rom24::kZ] == Approx(y0[Rom24::kZ]).margin(1e-4));
  for (int w = 0; w < 4; ++w) CHECK(y[Rom24::kWheelZ + w] == Approx(y0[Rom24::kWheelZ + w]).margin(1e-4));
  CHECK(std::hypot(y[Rom24::kX], y[Rom24::kY]) < 1e-6);
}

TEST_CASE("rom 24-DOF: braking pitches the nose down, accelerating lifts it", "[rom]") {
  const RomVehicle v = hmmwv();
  const RomRunResult brake = run(v, constant_inputs(0, 0, 0.5), options(RomModel::k24Dof, 1.0, 20.0));
  const RomRunResult accel = run(v, constant_inputs(0, 1, 0), options(RomModel::k24Dof, 1.0, 3.0));
  CHECK(brake.samples.back().pitch > 1e-3);  // ISO 8855: positive pitch is nose down
  CHECK(accel.samples.back().pitch < -1e-4);
}
