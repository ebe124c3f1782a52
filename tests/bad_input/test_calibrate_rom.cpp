// Bad input to `terracal calibrate-rom`: the options' values, refused before any run. (The references
// and parameter files have their cases beside the calibration tests, tests/apps/test_calibrate_rom.cpp.)
#include "bad_input_suite.hpp"

using terracal::test::BadInput;

TEST_CASE("bad input, calibrate-rom: options", "[cli][bad_input]") {
  const std::string base = "calibrate-rom --vehicle hmmwv --reference {dir} --out {out} ";
  const std::vector<BadInput> cases = {
      {"no least-squares start", {}, base + "--starts 0", {"--starts", "0", "[1, 100]"}},
      {"too many least-squares starts", {}, base + "--starts 101", {"--starts", "101", "[1, 100]"}},
      {"starts not a number", {}, base + "--starts three", {"--starts", "three"}},
      {"negative lookahead", {}, base + "--lookahead -1", {"--lookahead", "-1", "[0, 1000]"}},
      {"lookahead too long", {}, base + "--lookahead 1001", {"--lookahead", "1001", "[0, 1000]"}},
      {"negative global points", {}, base + "--global-points -1", {"--global-points", "-1"}},
      {"unknown sampler", {}, base + "--sampler gibbs", {"--sampler", "gibbs"}},
      {"unknown device", {}, base + "--device tpu", {"--device", "tpu"}},
      {"no --reference", {}, "calibrate-rom --vehicle hmmwv --out {out}", {"--reference"}},
  };
  terracal::test::check_bad_inputs("bad_calibrate_rom", cases);
}
