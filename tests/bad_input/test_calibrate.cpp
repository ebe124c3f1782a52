// Bad input to `terracal calibrate`: plate.csv, shear.csv, priors.json and the options.
#include "bad_input_suite.hpp"

using namespace std::string_literals;
using terracal::test::BadInput;
using terracal::test::check_bad_inputs;

namespace {

const std::string kHeader = "plate_radius_m,sinkage_m,force_N\n";
const std::string kPlate = kHeader + "0.1,0.01,100\n0.1,0.02,250\n";
const std::string kShearHeader = "inner_radius_m,outer_radius_m,normal_load_N,angle_rad,torque_Nm\n";

// A plate.csv case: the file, then calibrate on it with the demo's shear curves.
BadInput plate(const std::string& name, const std::string& csv, std::vector<std::string> phrases) {
  return {name,
          {{"plate.csv", csv}},
          "calibrate --plate {dir}/plate.csv --shear {demo}/shear.csv --out {out}",
          std::move(phrases)};
}
BadInput shear(const std::string& name, const std::string& csv, std::vector<std::string> phrases) {
  return {name,
          {{"shear.csv", csv}},
          "calibrate --plate {demo}/plate.csv --shear {dir}/shear.csv --out {out}",
          std::move(phrases)};
}
BadInput priors(const std::string& name, const std::string& json, std::vector<std::string> phrases) {
  return {name,
          {{"priors.json", json}},
          "calibrate --plate {demo}/plate.csv --priors {dir}/priors.json --out {out}",
          std::move(phrases)};
}
BadInput option(const std::string& args, std::vector<std::string> phrases) {
  return {args, {}, "calibrate --plate {demo}/plate.csv --out {out} " + args, std::move(phrases)};
}

std::string utf16le_with_bom(const std::string& ascii) {
  std::string out = "\xFF\xFE";
  for (const char c : ascii) out += std::string(1, c) + '\0';
  return out;
}

std::vector<BadInput> plate_cases() {
  const std::string demo_order = kHeader + "0.1,0.01,300\n0.1,0.02,650\n0.1,0.03,1000\n";
  return {
      plate("missing column", "plate_radius_m,force_N\n0.1,100\n", {"{dir}/plate.csv:1", "sinkage_m"}),
      plate("non-numeric cell", kHeader + "0.1,0.01,100\n0.1,abc,200\n",
            {"{dir}/plate.csv:3, column 'sinkage_m' (2)", "not a number"}),
      plate("NaN", kHeader + "0.1,0.01,nan\n", {"{dir}/plate.csv:2, column 'force_N' (3)", "finite"}),
      plate("negative sinkage", kHeader + "0.1,0.01,100\n0.1,-0.02,50\n",
            {"{dir}/plate.csv:3, column 'sinkage_m'", "negative"}),
      plate("negative radius", kHeader + "-0.1,0.01,100\n", {"{dir}/plate.csv:2, column 'plate_radius_m'", "> 0"}),
      plate("empty file", "", {"{dir}/plate.csv", "empty"}),
      plate("header only", kHeader, {"{dir}/plate.csv", "no data rows"}),
      plate("sinkage in millimetres", kHeader + "0.1,10,100\n0.1,20,200\n",
            {"{dir}/plate.csv:2, column 'sinkage_m'", "millimetres"}),
      plate("missing column after comments", "# rig 3\n# 2026-11-01\nplate_radius_m,force_N\n0.1,100\n",
            {"{dir}/plate.csv:3: missing column(s) sinkage_m"}),
      plate("negative force", kHeader + "0.1,0.01,-5\n", {"{dir}/plate.csv:2, column 'force_N' (3)", "negative"}),
      plate("all-zero forces", kHeader + "0.1,0.01,0\n0.1,0.02,0\n", {"{dir}/plate.csv", "zero"}),
      plate("unknown phase", kHeader.substr(0, kHeader.size() - 1) + ",phase\n0.1,0.01,100,press\n",
            {"{dir}/plate.csv:2, column 'phase' (4)", "load, unload or reload"}),
      plate("rows in reverse order", kHeader + "0.1,0.03,1000\n0.1,0.02,650\n0.1,0.01,300\n",
            {"{dir}/plate.csv:3, column 'sinkage_m'", "shallower than line 2", "order of the test"}),
      plate("rows shuffled", kHeader + "0.1,0.02,650\n0.1,0.03,1000\n0.1,0.01,300\n",
            {"{dir}/plate.csv:4, column 'sinkage_m'", "shallower than line 3"}),
      plate("a reload with no unload before it",
            kHeader.substr(0, kHeader.size() - 1) + ",phase\n0.1,0.01,300,load\n0.1,0.015,400,reload\n",
            {"{dir}/plate.csv:3, column 'phase'", "without an unload row"}),
      plate("UTF-16 text", utf16le_with_bom(demo_order),
            {"{dir}/plate.csv:1:1: found bytes FF FE 70 00 (the byte-order mark of UTF-16LE", "expected UTF-8 text"}),
      plate("Latin-1 text", "# r\xE9sultats\n" + demo_order, {"{dir}/plate.csv:1:4: found bytes E9"}),
      plate("a NUL byte", demo_order + "0.1,0.04,\0"s + "1400\n", {"{dir}/plate.csv:5:10: found bytes 00"}),
      plate("1e309", demo_order + "0.1,0.04,1e309\n",
            {"{dir}/plate.csv:5, column 'force_N' (3): '1e309' is out of range for a double"}),
      plate("a huge cell", demo_order + "0.1,0.04," + std::string(100000, '7') + "\n",
            {"{dir}/plate.csv:5: the line is longer than 65536 bytes", "(100009 characters)"}),
      plate("more cells than the header", demo_order + "0.1,0.04,1400,7\n", {"{dir}/plate.csv:5: 4 cells"}),
  };
}

std::vector<BadInput> shear_cases() {
  return {
      shear("negative angle", kShearHeader + "0.15,0.2,100,-0.1,5\n", {"{dir}/shear.csv:2, column 'angle_rad' (4)"}),
      shear("outer radius below inner", kShearHeader + "0.2,0.15,100,0.1,5\n",
            {"{dir}/shear.csv:2, column 'outer_radius_m'"}),
      shear("zero load", kShearHeader + "0.15,0.2,0,0.1,5\n", {"{dir}/shear.csv:2, column 'normal_load_N'", "> 0"}),
      shear("missing torque column", "inner_radius_m,outer_radius_m,normal_load_N,angle_rad\n0.15,0.2,100,0.1\n",
            {"{dir}/shear.csv:1: missing column(s) torque_Nm"}),
      shear("only rows at angle 0", kShearHeader + "0.15,0.2,100,0,0\n",
            {"{dir}/shear.csv", "no rows with a shear angle > 0"}),
  };
}

std::vector<BadInput> priors_cases() {
  return {
      priors("unknown key", R"({"Kphii": {"type": "uniform", "lower": 0, "upper": 1e7}})", {"unknown key 'Kphii'"}),
      priors("bound out of range", R"({"phi": {"type": "uniform", "lower": 0, "upper": 75}})",
             {"'phi.upper': 75 is outside the physical range [0, 60]"}),
      priors("open lower bound", R"({"k": {"type": "uniform", "lower": 0, "upper": 0.1}})",
             {"'k.lower': 0 is outside the physical range (0, 10]"}),
      priors("number out of range", R"({"c": {"type": "uniform", "lower": 0, "upper": 1e400}})",
             {"{dir}/priors.json:1:48: key 'c.upper': '1e400' is out of range for a double"}),
      priors("everything fixed",
             R"({"Kc": {"type": "fixed", "value": 0}, "Kphi": {"type": "fixed", "value": 1e6}, )"
             R"("n": {"type": "fixed", "value": 1}})",
             {"every parameter is fixed"}),
      priors("duplicate key",
             "{\"n\": {\"type\": \"normal\", \"mean\": 1, \"sd\": 0.2},\n \"n\": {\"type\": \"fixed\", \"value\": 1}}",
             {"{dir}/priors.json:2:2: key 'n': duplicate key (first at line 1, column 2)"}),
      priors("misspelt field", R"({"Kphi": {"type": "uniform", "lower": 0, "uper": 1e7}})",
             {"key 'Kphi.uper': unknown key for a uniform prior; expected type, lower, upper"}),
      priors("a field the prior type does not take", R"({"Kc": {"type": "fixed", "value": 0, "upper": 1}})",
             {"key 'Kc.upper': unknown key for a fixed prior; expected type, value"}),
      priors(
          "one parameter under two names",
          R"({"Kphi": {"type": "uniform", "lower": 0, "upper": 1e7}, "Bekker Kphi": {"type": "fixed", "value": 1e6}})",
          {"keys 'Bekker Kphi' and 'Kphi' both give the prior of Kphi"}),
      priors("not JSON", "{\"n\": {\"type\": \"normal\",\n \"mean\": }", {"{dir}/priors.json:2:10", "not valid JSON"}),
  };
}

const std::string kWheelHeader = "slip,load_N,dbp_N,torque_Nm,sinkage_m\n";
const std::string kWheelRows = "0.1,1000,300,200,0.03\n0.3,1000,350,250,0.05\n";
const std::string kWheelSpec = R"({"radius": 0.47, "width": 0.25, "mass": 108})";

// A wheel.csv case: the file and its wheel, then calibrate on it with the demo's bevameter curves.
BadInput wheel(const std::string& name, const std::string& csv, std::vector<std::string> phrases) {
  return {name,
          {{"wheel.csv", csv}, {"wheel.json", kWheelSpec}},
          "calibrate --plate {demo}/plate.csv --shear {demo}/shear.csv --wheel {dir}/wheel.csv --wheel-spec "
          "{dir}/wheel.json --out {out}",
          std::move(phrases)};
}

std::vector<BadInput> wheel_cases() {
  return {
      wheel("missing column", "slip,load_N,dbp_N,torque_Nm\n0.1,1000,300,200\n", {"{dir}/wheel.csv:1", "sinkage_m"}),
      wheel("slip 1", kWheelHeader + kWheelRows + "1,1000,400,300,0.1\n",
            {"{dir}/wheel.csv:4, column 'slip'", "outside [0, 1)"}),
      wheel("skid", kWheelHeader + "-0.2,1000,-300,-100,0.03\n" + kWheelRows,
            {"{dir}/wheel.csv:2, column 'slip'", "skids"}),
      wheel("load 0", kWheelHeader + "0.1,0,300,200,0.03\n0.3,1000,350,250,0.05\n",
            {"{dir}/wheel.csv:2, column 'load_N'", "must be > 0"}),
      wheel("sinkage in millimetres", kWheelHeader + "0.1,1000,300,200,30\n0.3,1000,350,250,50\n",
            {"{dir}/wheel.csv:2, column 'sinkage_m'", "millimetres"}),
      wheel("the same slip twice", kWheelHeader + kWheelRows + "0.1,1000,310,205,0.031\n",
            {"{dir}/wheel.csv:4, column 'slip'", "a second row for slip 0.1"}),
      wheel("one row", kWheelHeader + "0.1,1000,300,200,0.03\n", {"{dir}/wheel.csv", "at least 2 slips"}),
      wheel("non-numeric pull", kWheelHeader + "0.1,1000,abc,200,0.03\n0.3,1000,350,250,0.05\n",
            {"{dir}/wheel.csv:2, column 'dbp_N'"}),
      {"no wheel geometry",
       {{"wheel.csv", kWheelHeader + kWheelRows}},
       "calibrate --plate {demo}/plate.csv --wheel {dir}/wheel.csv --out {out}",
       {"--wheel {dir}/wheel.csv", "--wheel-spec", "run.json"}},
      {"run.json without its wheel",
       {{"wheel.csv", kWheelHeader + kWheelRows}, {"run.json", R"({"terrain": "crm"})"}},
       "calibrate --plate {demo}/plate.csv --wheel {dir}/wheel.csv --out {out}",
       {"{dir}/run.json", "key 'wheel'"}},
      {"run.json with a bad wheel",
       {{"wheel.csv", kWheelHeader + kWheelRows}, {"run.json", R"({"wheel": {"radius": -1, "width": 0.25, "mass": 1}})"}},
       "calibrate --plate {demo}/plate.csv --wheel {dir}/wheel.csv --out {out}",
       {"{dir}/run.json", "radius", "-1"}},
      {"--wheel-spec without --wheel",
       {{"wheel.json", kWheelSpec}},
       "calibrate --plate {demo}/plate.csv --wheel-spec {dir}/wheel.json --out {out}",
       {"--wheel-spec {dir}/wheel.json: only with --wheel"}},
      {"--annulus-law scaled without wheel curves",
       {},
       "calibrate --plate {demo}/plate.csv --shear {demo}/shear.csv --annulus-law scaled --out {out}",
       {"--annulus-law scaled", "--wheel", "no wheel curves"}},
      {"--annulus-law scaled without shear curves",
       {{"wheel.csv", kWheelHeader + kWheelRows}, {"wheel.json", kWheelSpec}},
       "calibrate --plate {demo}/plate.csv --wheel {dir}/wheel.csv --wheel-spec {dir}/wheel.json --annulus-law scaled "
       "--out {out}",
       {"--annulus-law scaled", "--shear", "no shear curves"}},
      {"a prior for R at zero",
       {{"priors.json", R"({"R": {"type": "uniform", "lower": 0, "upper": 5}})"}},
       "calibrate --plate {demo}/plate.csv --priors {dir}/priors.json --out {out}",
       {"{dir}/priors.json", "R.lower", "0"}},
      {"a prior for S outside its range",
       {{"priors.json", R"({"S": {"type": "uniform", "lower": 0, "upper": 50}})"}},
       "calibrate --plate {demo}/plate.csv --priors {dir}/priors.json --out {out}",
       {"{dir}/priors.json", "S.upper", "50"}},
  };
}

std::vector<BadInput> option_cases() {
  return {
      option("--chains 3", {"--chains 3: expected 4 to 256 chains"}),
      option("--max-draws -5", {"--max-draws -5"}),
      option("--sampler gibbs", {"--sampler: 'gibbs' is not one of dram|ensemble"}),
      option("--noise loud", {"--noise", "loud"}),
      option("--annulus-law loose", {"--annulus-law: 'loose' is not one of scaled|shared"}),
      option("--min-ess 0", {"--min-ess: value 0 is outside (0, 1000000000]"}),
      option("--elastic-stiffness -4e7", {"--elastic-stiffness: value -4e7 is outside 0 (off) or [1, 10000000000000] Pa/m"}),
      option("--elastic-stiffness 1e14", {"--elastic-stiffness: value 1e14 is outside 0 (off) or [1, 10000000000000] Pa/m"}),
      option("--elastic-stiffness soft", {"--elastic-stiffness", "soft"}),
      option("--min-ess -1", {"--min-ess: value -1 is outside (0, 1000000000]"}),
      option("--seed 1.5", {"--seed: value 1.5 is not a whole number"}),
      option("--chains 1e3", {"--chains: value 1e3 is not a whole number"}),
      option("--chains 3.5", {"--chains: value 3.5 is not a whole number"}),
      option("--chains 300", {"--chains 300: expected 4 to 256 chains"}),
      option("--max-draws 99999999999999999999", {"--max-draws: value 99999999999999999999 is outside"}),
      option("--max-draws 1000000000", {"--max-draws 1000000000: expected 10 to 100000000"}),
      option("--chains 256 --max-draws 100000000",
             {"--max-draws 100000000 with --chains 256: keeping 1e+08 draws of 256 chains until the cap needs about",
              "expected fewer --max-draws or --chains"}),
      {"--out is a file",
       {{"afile", "x\n"}},
       "calibrate --plate {demo}/plate.csv --out {dir}/afile",
       {"--out {dir}/afile: exists and is not a folder"}},
      {"a plate file that does not exist", {}, "calibrate --plate {dir}/none.csv --out {out}", {"{dir}/none.csv"}},
      {"no --plate", {}, "calibrate --out {out}", {"--plate"}},
  };
}

}  // namespace

TEST_CASE("bad input, calibrate: plate.csv", "[cli][bad_input]") { check_bad_inputs("bad_plate", plate_cases()); }
TEST_CASE("bad input, calibrate: shear.csv", "[cli][bad_input]") { check_bad_inputs("bad_shear", shear_cases()); }
TEST_CASE("bad input, calibrate: priors.json", "[cli][bad_input]") { check_bad_inputs("bad_priors", priors_cases()); }
TEST_CASE("bad input, calibrate: options", "[cli][bad_input]") { check_bad_inputs("bad_calopt", option_cases()); }
TEST_CASE("bad input, calibrate: wheel.csv", "[cli][bad_input]") { check_bad_inputs("bad_calwheel", wheel_cases()); }
