// Bad input to `terracal pipeline`: its soil and options, all refused before the bed settles.
#include "bad_input_suite.hpp"

using terracal::test::BadInput;

namespace {

BadInput option(const std::string& args, std::vector<std::string> phrases) {
  return {args, {}, "pipeline --soil {soil} --device cpu --out {out} " + args, std::move(phrases)};
}

}  // namespace

TEST_CASE("bad input, pipeline", "[cli][bad_input]") {
  const std::vector<BadInput> cases = {
      {"soil of negative density",
       {{"soil.json", R"({"density": -5, "young_modulus": 1e6, "poisson_ratio": 0.3, "mu_s": 0.7, "mu_2": 0.7,
          "I0": 0.03, "grain_diameter": 0.005, "cohesion": 0, "gravity": [0, 0, -9.81]})"}},
       "pipeline --soil {dir}/soil.json --out {out}",
       {"density", "-5"}},
      option("--seed -5", {"--seed: value -5 is outside"}),
      option("--shear-loads 490,-3", {"--shear-loads", "-3"}),
      option("--plates 0.1,0.1", {"--plates 0.1,0.1: the value 0.1 is given twice"}),
      option("--annulus 0.15", {"--annulus"}),
      option("--checks=annulus,plates", {"--checks", "plates"}),
      option("--checks --check-realisations 0", {"--check-realisations", "0"}),
      option("--check-realisations 17", {"--check-realisations: value 17 is outside [1, 16]"}),
      option("--hourglass-damping -1", {"--hourglass-damping", "-1"}),
      option("--h-over-d0 1.7", {"--h-over-d0", "1.7"}),
      option("--marker-velocity adami", {"--marker-velocity", "adami"}),
      option("--plate-depth-scale 0.1", {"--plate-depth-scale", "0.1"}),
      option("--wheel-duration -1", {"--wheel-duration: value -1 is outside"}),
      option("--calibrate-on wheel", {"--calibrate-on", "wheel"}),
      option("--calibration-slips 0.1,0.25", {"--calibration-slips: slip 0.25 is not among --slips"}),
      option("--calibrate-on bevameter --annulus-law shared",
             {"--annulus-law: only with --calibrate-on bevameter+wheel"}),
      option("--annulus-law tight", {"--annulus-law: 'tight' is not one of scaled|shared"}),
      option("--elastic-stiffness -2e6", {"--elastic-stiffness: value -2e6 is outside 0 (off) or [1, 10000000000000] Pa/m"}),
      option("--calibrate-on bevameter --calibration-slips 0.1",
             {"--calibration-slips: only with --calibrate-on bevameter+wheel"}),
      option("--spacing 0.001", {"--spacing 0.001 m: a CRM bin", "needs about"}),
      {"--out is a file",
       {{"afile", "x\n"}},
       "pipeline --soil {soil} --out {dir}/afile",
       {"--out {dir}/afile: exists and is not a folder"}},
  };
  terracal::test::check_bad_inputs("bad_pipeline", cases);
}
