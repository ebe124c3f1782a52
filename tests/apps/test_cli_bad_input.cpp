// Every kind of bad input gives exit code 2, a message naming the file, line
// and column, and no output files.
#include <catch2/catch.hpp>

#include <filesystem>

#include "cli_runner.hpp"

using namespace terracal::test;
namespace fs = std::filesystem;

namespace {

struct BadCase {
  const char* name;
  const char* plate_csv;
  const char* expect_line;  // "file:LINE" fragment expected in the message
  const char* expect_text;  // a word the message must contain
};

const BadCase kCases[] = {
    {"missing column", "plate_radius_m,force_N\n0.1,100\n", ":1", "sinkage_m"},
    {"non-numeric cell", "plate_radius_m,sinkage_m,force_N\n0.1,0.01,100\n0.1,abc,200\n", ":3, column 'sinkage_m' (2)",
     "not a number"},
    {"NaN", "plate_radius_m,sinkage_m,force_N\n0.1,0.01,nan\n", ":2, column 'force_N' (3)", "finite"},
    {"negative sinkage", "plate_radius_m,sinkage_m,force_N\n0.1,0.01,100\n0.1,-0.02,50\n", ":3, column 'sinkage_m'",
     "negative"},
    {"negative radius", "plate_radius_m,sinkage_m,force_N\n-0.1,0.01,100\n", ":2, column 'plate_radius_m'", "> 0"},
    {"empty file", "", "plate.csv", "empty"},
    {"header only", "plate_radius_m,sinkage_m,force_N\n", "plate.csv", "no data rows"},
    {"sinkage in millimetres", "plate_radius_m,sinkage_m,force_N\n0.1,10,100\n0.1,20,200\n", ":2, column 'sinkage_m'",
     "millimetres"},
    {"missing column after comments", "# rig 3\n# 2026-11-01\nplate_radius_m,force_N\n0.1,100\n",
     "plate.csv:3: missing column(s) sinkage_m", "sinkage_m"},
    {"negative force", "plate_radius_m,sinkage_m,force_N\n0.1,0.01,-5\n", ":2, column 'force_N' (3)", "negative"},
    {"all-zero forces", "plate_radius_m,sinkage_m,force_N\n0.1,0.01,0\n0.1,0.02,0\n", "plate.csv", "zero"},
    {"unknown phase", "plate_radius_m,sinkage_m,force_N,phase\n0.1,0.01,100,press\n", ":2, column 'phase' (4)",
     "load, unload or reload"},
};

}  // namespace

TEST_CASE("bad plate input: exit 2, the message names file, line and column, no output", "[cli][bad_input]") {
  for (const auto& c : kCases) {
    SECTION(c.name) {
      const ScratchDir scratch("bad");
      const std::string dir = scratch.str();
      write(dir + "/plate.csv", c.plate_csv);
      const std::string out = dir + "/out";
      const CliResult r =
          run_cli("calibrate --plate " + dir + "/plate.csv --shear " + demo_data("shear.csv") + " --out " + out, dir);
      INFO(c.name << ": stderr was: " << r.err);
      CHECK(r.exit_code == 2);
      CHECK(r.err.find(dir + "/plate.csv") != std::string::npos);
      CHECK(r.err.find(c.expect_line) != std::string::npos);
      CHECK(r.err.find(c.expect_text) != std::string::npos);
      CHECK_FALSE(fs::exists(out));
    }
  }
}

TEST_CASE("bad shear input and bad options: exit 2 naming what is wrong", "[cli][bad_input]") {
  const ScratchDir scratch("badshear");
  const std::string dir = scratch.str();
  const std::string out = dir + "/out";
  // Bad shear files and priors files: {case, file, content, option that passes it, expected message}.
  struct FileCase {
    const char* name;
    const char* file;
    const char* content;
    const char* option;
    const char* expect;
  };
  const FileCase cases[] = {
      {"negative angle", "shear.csv",
       "inner_radius_m,outer_radius_m,normal_load_N,angle_rad,torque_Nm\n0.15,0.2,100,-0.1,5\n", "--shear",
       "shear.csv:2, column 'angle_rad' (4)"},
      {"outer radius below inner", "shear.csv",
       "inner_radius_m,outer_radius_m,normal_load_N,angle_rad,torque_Nm\n0.2,0.15,100,0.1,5\n", "--shear",
       "shear.csv:2, column 'outer_radius_m'"},
      {"priors: unknown key", "priors.json", R"({"Kphii": {"type": "uniform", "lower": 0, "upper": 1e7}})", "--priors",
       "unknown key 'Kphii'"},
      {"priors: bound out of range", "priors.json", R"({"phi": {"type": "uniform", "lower": 0, "upper": 75}})",
       "--priors", "'phi.upper': 75 is outside the physical range [0, 60]"},
      {"priors: open lower bound", "priors.json", R"({"k": {"type": "uniform", "lower": 0, "upper": 0.1}})", "--priors",
       "'k.lower': 0 is outside the physical range (0, 10]"},
      {"priors: number out of range", "priors.json", R"({"c": {"type": "uniform", "lower": 0, "upper": 1e400}})",
       "--priors", "priors.json:1:48: key 'c.upper': '1e400' is out of range"},
      {"priors: everything fixed", "priors.json",
       R"({"Kc": {"type": "fixed", "value": 0}, "Kphi": {"type": "fixed", "value": 1e6}, )"
       R"("n": {"type": "fixed", "value": 1}})",
       "--priors", "every parameter is fixed"},
  };
  for (const auto& c : cases) {
    SECTION(c.name) {
      write(dir + "/" + c.file, c.content);
      const CliResult r = run_cli(
          "calibrate --plate " + demo_data("plate.csv") + " " + c.option + " " + dir + "/" + c.file + " --out " + out,
          dir);
      INFO(c.name << ": stderr was: " << r.err);
      CHECK(r.exit_code == 2);
      CHECK(r.err.find(c.expect) != std::string::npos);
    }
  }
  SECTION("options") {
    CliResult r = run_cli("calibrate --plate " + demo_data("plate.csv") + " --chains 3 --out " + out, dir);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--chains 3: expected 4 to 256 chains") != std::string::npos);
    r = run_cli("calibrate --plate " + demo_data("plate.csv") + " --max-draws -5 --out " + out, dir);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--max-draws -5") != std::string::npos);
    r = run_cli("calibrate --plate " + demo_data("plate.csv") + " --sampler gibbs --out " + out, dir);
    CHECK(r.exit_code == 2);
    CHECK(r.err.find("--sampler: 'gibbs' is not one of dram|ensemble") != std::string::npos);
    r = run_cli("calibrate --plate /nonexistent.csv --out " + out, dir);
    CHECK(r.exit_code == 2);
    r = run_cli("frobnicate", dir);
    CHECK(r.exit_code == 2);
  }
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("--help and --version exit 0", "[cli]") {
  const ScratchDir scratch("help");
  const std::string dir = scratch.str();
  CliResult r = run_cli("--version", dir);
  CHECK(r.exit_code == 0);
  CHECK(r.out.find("terracal ") == 0);
  r = run_cli("calibrate --help", dir);
  CHECK(r.exit_code == 0);
  CHECK(r.out.find("--min-ess") != std::string::npos);
}
