// Bad input to `terracal synthesize`: the SCM set of --truth (read by the same validator as wheel
// and bevameter read it) and the design options.
#include <nlohmann/json.hpp>

#include "bad_input_suite.hpp"

using terracal::test::BadInput;
using terracal::test::InputFile;

namespace {

// The demo's truth.json with one soil parameter set to `value`.
InputFile truth_with(const std::string& name, const std::string& key, double value) {
  nlohmann::json j = nlohmann::json::parse(terracal::test::read_file(terracal::test::demo_data("truth.json")));
  j["Soil parameters"][key] = value;
  return {name, j.dump()};
}

BadInput option(const std::string& args, std::vector<std::string> phrases) {
  return {args, {}, "synthesize --truth {demo}/truth.json --out {out} " + args, std::move(phrases)};
}
BadInput truth(const std::string& name, InputFile file, std::vector<std::string> phrases) {
  const std::string args = "synthesize --truth {dir}/" + file.name + " --out {out}";
  return {name, {std::move(file)}, args, std::move(phrases)};
}

}  // namespace

TEST_CASE("bad input, synthesize: --truth", "[cli][bad_input]") {
  const std::vector<BadInput> cases = {
      truth("Janosi k = 0", truth_with("k0.json", "Janosi shear coefficient", 0),
            {"k0.json: key 'Soil parameters.Janosi shear coefficient' = 0: expected in [1e-06, 10] m"}),
      truth("friction angle 95 degrees", truth_with("phi95.json", "Mohr friction limit", 95),
            {"key 'Soil parameters.Mohr friction limit' = 95"}),
      truth("n = 0", truth_with("n0.json", "Bekker n exponent", 0), {"key 'Soil parameters.Bekker n exponent' = 0"}),
      truth("a misspelt key", truth_with("typo.json", "Bekker Kx", 1), {"unknown key 'Soil parameters.Bekker Kx'"}),
      truth("not JSON", {"broken.json", "{\"Soil parameters\": {\n  \"Bekker Kphi\": }"},
            {"{dir}/broken.json:2", "not valid JSON"}),
      {"a file that does not exist", {}, "synthesize --truth {dir}/none.json --out {out}", {"{dir}/none.json"}},
  };
  terracal::test::check_bad_inputs("bad_synth_truth", cases);
}

TEST_CASE("bad input, synthesize: options", "[cli][bad_input]") {
  const std::vector<BadInput> cases = {
      // Every --seed takes [0, 2^64 - 1] and nothing else (CLI11 alone wraps -1 to 2^64 - 1).
      option("--seed -1", {"--seed: value -1 is outside [0, 18446744073709551615]"}),
      option("--seed 18446744073709551616", {"--seed: value 18446744073709551616 is outside"}),
      option("--plate-points 1e3", {"--plate-points: value 1e3 is not a whole number in [1, 100000]"}),
      option("--shear-points 0", {"--shear-points: value 0 is outside [1, 100000]"}),
      // Above 0.2 a 5-sigma draw would make a force negative (docs/formats.md).
      option("--noise 0.3", {"--noise: value 0.3 is outside [0, 0.2]"}),
      option("--plates 0.1,-0.2", {"--plates: value -0.2 is outside (0, 10] m"}),
      option("--plates 0.2,0.1,0.2", {"--plates 0.2,0.1,0.2: the value 0.2 is given twice"}),
      option("--annulus 0.2,0.15", {"--annulus 0.2,0.15: expected the inner radius below the outer one"}),
  };
  terracal::test::check_bad_inputs("bad_synth_opt", cases);
}
