// Bad input to `terracal pipeline-rom`: the vehicles and the options, refused before any run.
#include "bad_input_suite.hpp"

using terracal::test::BadInput;

TEST_CASE("bad input, pipeline-rom: vehicles and options", "[cli][bad_input]") {
  const std::vector<BadInput> cases = {
      {"no such full vehicle", {}, "pipeline-rom --vehicle {dir}/none.json --out {out}", {"{dir}/none.json"}},
      {"no such ROM vehicle",
       {},
       "pipeline-rom --rom-vehicle {dir}/rom.json --out {out}",
       {"{dir}/rom.json"}},
      {"unknown model", {}, "pipeline-rom --model 30dof --out {out}", {"--model", "30dof"}},
      {"no draws", {}, "pipeline-rom --draws 0 --out {out}", {"--draws", "0"}},
      {"too few calibration draws", {}, "pipeline-rom --max-draws 5 --out {out}", {"--max-draws", "5"}},
      {"unknown device", {}, "pipeline-rom --device tpu --out {out}", {"--device", "tpu"}},
      {"no --out", {}, "pipeline-rom", {"--out"}},
  };
  terracal::test::check_bad_inputs("bad_pipeline_rom", cases);
}
