// Bad input to `terracal demo`: its options (it reads no file of the user's).
#include "bad_input_suite.hpp"

using terracal::test::BadInput;

TEST_CASE("bad input, demo", "[cli][bad_input]") {
  const std::vector<BadInput> cases = {
      {"--seed 0x10",
       {},
       "demo --calibration-only --out {out} --seed 0x10",
       {"--seed: value 0x10 is not a whole number"}},
      {"--seed -1", {}, "demo --calibration-only --out {out} --seed -1", {"--seed: value -1 is outside"}},
      {"--out is a file",
       {{"afile", "x\n"}},
       "demo --calibration-only --out {dir}/afile",
       {"--out {dir}/afile: exists and is not a folder"}},
  };
  terracal::test::check_bad_inputs("bad_demo", cases);
}
