// Bad input to `terracal wheel`: the wheel file (--wheel), the soil and the options. And the one
// suspicious but legitimate input, a wheel that does not turn, which runs with a warning.
#include "bad_input_suite.hpp"

using terracal::test::BadInput;
using terracal::test::InputFile;

namespace {

const std::string kScm = "wheel --terrain scm --scm {demo}/truth.json --wheel {dir}/wheel.json --out {out} ";

std::vector<InputFile> wheel_files() {
  return {{"wheel.json", R"({"radius": 0.47, "width": 0.25, "mass": 108, "angular_velocity": 1.0})"},
          {"wheel_typo.json", R"({"radius": 0.47, "widht": 0.25, "mass": 108})"},
          {"wheel_neg.json", R"({"radius": -0.47, "width": 0.25, "mass": 108})"},
          {"wheel_massless.json", R"({"radius": 0.47, "width": 0.25, "mass": 0})"}};
}

BadInput scm(const std::string& args, std::vector<std::string> phrases) {
  return {args, {}, kScm + args, std::move(phrases)};
}
BadInput wheel(const std::string& file, std::vector<std::string> phrases) {
  return {file,
          {},
          "wheel --terrain scm --scm {demo}/truth.json --wheel {dir}/" + file + " --out {out}",
          std::move(phrases)};
}

}  // namespace

TEST_CASE("bad input, wheel: the wheel file", "[cli][bad_input]") {
  const std::vector<BadInput> cases = {
      wheel("wheel_typo.json", {"width", "missing"}),
      wheel("wheel_neg.json", {"radius", "-0.47"}),
      wheel("wheel_massless.json",
            {"wheel_massless.json: key 'mass': value 0 is outside the allowed range (0, 1000000]"}),
      wheel("none.json", {"{dir}/none.json"}),
  };
  terracal::test::check_bad_inputs("bad_wheel_file", cases, wheel_files());
}

TEST_CASE("bad input, wheel: options", "[cli][bad_input]") {
  const std::vector<BadInput> cases = {
      scm("--slips 0.2,1.5", {"--slips: value 1.5 in the list '0.2,1.5' is outside (-1, 1)"}),
      scm("--slips 0,,0.2", {"--slips: value '0,,0.2' is not a comma-separated list"}),
      scm("--duration 0", {"--duration: value 0 is outside [0.001, 100000] s"}),
      scm("--average-from 1", {"--average-from: value 1 is outside [0, 0.95]"}),
      scm("--gravity 0 0 9.81", {"--gravity [0, 0, 9.81] m/s^2: expected gravity pointing down"}),
      scm("--gravity 0 0 0", {"--gravity [0, 0, 0] m/s^2: expected gravity"}),
      scm("--device cpu", {"--device: for CRM only; --solver/--terrain scm does not read it"}),
      scm("--concurrent-runs 2", {"--concurrent-runs: for CRM only; --solver/--terrain scm does not read it"}),
      scm("--drop-height 3", {"--drop-height: value 3 is outside [0, 2] m"}),
      scm("--wong-reece-slip-sinkage", {"--wong-reece-slip-sinkage: only with --terrain wong-reece"}),
      {"a slip-sinkage coefficient out of range",
       {{"slip.json", R"({"Soil parameters": {"Bekker Kc": 990, "Bekker Kphi": 1528430, "Bekker n exponent": 1.1,
          "Mohr cohesive limit": 1040, "Mohr friction limit": 28, "Janosi shear coefficient": 0.025},
          "Slip sinkage": {"Model": "Lyasko", "S": 50}})"}},
       "wheel --terrain scm --scm {dir}/slip.json --wheel {dir}/wheel.json --scm-effects damping slip_sinkage --out {out}",
       {"slip.json: key 'Slip sinkage.S' = 50: expected in [0, 20]"}},
      {"a drop on the steady Wong-Reece model",
       {},
       "wheel --terrain wong-reece --scm {demo}/truth.json --wheel {dir}/wheel.json --drop-height 0.1 --out {out}",
       {"--drop-height 0.1 m", "Wong-Reece is a steady model"}},
      {"--scm-effects with Wong-Reece",
       {},
       "wheel --terrain wong-reece --scm {demo}/truth.json --wheel {dir}/wheel.json --scm-effects none --out {out}",
       {"--scm-effects: for SCM only; --solver/--terrain wong-reece does not read it"}},
      {"unknown terrain",
       {},
       "wheel --terrain dem --scm {demo}/truth.json --wheel {dir}/wheel.json --out {out}",
       {"--terrain", "dem"}},
      {"CRM without --soil",
       {},
       "wheel --terrain crm --scm {demo}/truth.json --wheel {dir}/wheel.json --out {out}",
       {"--soil"}},
      {"--h-over-d0 0.9",
       {},
       "wheel --terrain crm --soil {soil} --wheel {dir}/wheel.json --device cpu --h-over-d0 0.9 --out {out}",
       {"--h-over-d0", "0.9"}},
      {"--marker-velocity slip",
       {},
       "wheel --terrain crm --soil {soil} --wheel {dir}/wheel.json --device cpu --marker-velocity slip --out {out}",
       {"--marker-velocity", "slip"}},
      {"--out is a file",
       {{"afile", "x\n"}},
       "wheel --terrain scm --scm {demo}/truth.json --wheel {dir}/wheel.json --out {dir}/afile",
       {"--out {dir}/afile: exists and is not a folder"}},
      {"CRM spacing beyond memory",
       {},
       "wheel --terrain crm --soil {soil} --device cpu --wheel {dir}/wheel.json --spacing 0.001 --out {out}",
       {"--spacing 0.001 m: a CRM bin", "for the wheel", "needs about"}},
  };
  terracal::test::check_bad_inputs("bad_wheel_opt", cases, wheel_files());
}

TEST_CASE("a wheel that does not turn runs, with a 'warning' line on stderr", "[cli][bad_input]") {
  const std::vector<BadInput> cases = {
      {"angular velocity 0",
       {{"still.json", R"({"radius": 0.47, "width": 0.25, "mass": 108, "angular_velocity": 0})"}},
       "wheel --terrain wong-reece --scm {demo}/truth.json --wheel {dir}/still.json --slips 0,0.2 --no-plots --out "
       "{out}",
       {"warning", "angular_velocity is 0: it does not turn"},
       0},
  };
  terracal::test::check_bad_inputs("warn_wheel", cases);
}
