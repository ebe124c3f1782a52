// The double-wishbone reader refuses bad input, naming the key, the value and what was expected.
#include <catch2/catch.hpp>

#include "core/errors.hpp"
#include "highfi/vehicle/double_wishbone.hpp"
#include "tests/highfi/vehicle/hmmwv_front_suspension.hpp"

using namespace terracal;

namespace {
std::string error_of(const nlohmann::json& j) {
  try {
    vehicle::read_double_wishbone(JsonObject(j, "front.json", "suspension"));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("suspension JSON: bad values are refused with the key named", "[vehicle][bad_input]") {
  const nlohmann::json good = test::hmmwv_front_suspension_json();
  CHECK(error_of(good).empty());
  nlohmann::json j = good;
  j["upright"]["mass"] = -2;
  CHECK_THAT(error_of(j), Catch::Contains("suspension.upright.mass") && Catch::Contains("-2"));
  j = good;
  j["lower_arm"]["chassis_back"] = j["lower_arm"]["chassis_front"];
  CHECK_THAT(error_of(j), Catch::Contains("suspension.lower_arm.chassis_back"));
  j = good;
  j["spring"]["curve"][3][0] = -0.5;
  CHECK_THAT(error_of(j), Catch::Contains("suspension.spring.curve") && Catch::Contains("row 3"));
  j = good;
  j["shock"]["dampng"] = 10;
  CHECK_THAT(error_of(j), Catch::Contains("dampng"));
  j = good;
  j["spindle"]["com"] = {0, 1};
  CHECK_THAT(error_of(j), Catch::Contains("suspension.spindle.com") && Catch::Contains("[x, y, z]"));
  j = good;
  j["upper_arm"]["inertia"] = {0.03, 0, 0.06};
  CHECK_THAT(error_of(j), Catch::Contains("suspension.upper_arm.inertia"));
}
