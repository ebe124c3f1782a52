// What the program says for a command line or an input file it cannot take: exit code 2 and a
// message naming what was found and what was expected.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "cli_runner.hpp"

using namespace terracal::test;
namespace fs = std::filesystem;

namespace {

// cli_runner's write() stops at the first NUL byte; these files have them.
void write_bytes(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

std::string utf16le_with_bom(const std::string& ascii) {
  std::string out = "\xFF\xFE";
  for (const char c : ascii) out += std::string(1, c) + '\0';
  return out;
}

}  // namespace

TEST_CASE("command line: unknown commands and options exit 2 naming them and what was expected", "[cli][messages]") {
  const ScratchDir scratch("cli_messages");
  const std::string dir = scratch.str();
  struct Case {
    const char* args;
    std::vector<const char*> phrases;
  };
  const Case cases[] = {
      {"frobnicate",
       {"terracal: unknown command 'frobnicate'; expected one of calibrate, demo, synthesize, crm, bevameter, wheel, "
        "pipeline"}},
      {"calibrte --plate x.csv", {"unknown command 'calibrte' (did you mean 'calibrate'?)"}},
      {"", {"terracal: a command is required; expected one of calibrate, demo,"}},
      {"--frobnicate", {"terracal: unknown option '--frobnicate'"}},
      {"calibrate --plat x.csv --out o",
       {"terracal calibrate: unknown option '--plat' (did you mean '--plate'?)",
        "'terracal calibrate --help' lists the options"}},
      {"calibrate --plate=x.csv --sed=3 --out o", {"unknown option '--sed' (did you mean '--seed'?)"}},
      {"calibrate --frobnicate 3 --out o", {"terracal calibrate: unknown option '--frobnicate';"}},
  };
  for (const auto& c : cases) {
    SECTION(std::string("terracal ") + c.args) {
      const CliResult r = run_cli(c.args, dir);
      INFO("stderr was: " << r.err);
      CHECK(r.exit_code == 2);
      for (const auto* p : c.phrases) CHECK(r.err.find(p) != std::string::npos);
    }
  }
}

TEST_CASE("command line: input files in another encoding or with bad numbers exit 2 naming file and line",
          "[cli][messages]") {
  const ScratchDir scratch("cli_files");
  const std::string dir = scratch.str();
  const std::string out = dir + "/out";
  const std::string plate = "plate_radius_m,sinkage_m,force_N\n0.1,0.01,100\n0.1,0.02,250\n";
  struct Case {
    const char* name;
    const char* file;
    std::string bytes;
    const char* option;
    std::string expect;  // follows the file's path in the message
  };
  const Case cases[] = {
      {"UTF-16 plate.csv", "plate.csv", utf16le_with_bom(plate), "--plate",
       ":1:1: found bytes FF FE 70 00 (the byte-order mark of UTF-16LE; save the file as UTF-8); expected UTF-8 text"},
      {"Latin-1 plate.csv", "plate.csv", "# r\xE9sultats\n" + plate, "--plate", ":1:4: found bytes E9"},
      {"1e309 in plate.csv", "plate.csv", plate + "0.1,0.03,1e309\n", "--plate",
       ":4, column 'force_N' (3): '1e309' is out of range for a double"},
      {"duplicate key in priors.json", "priors.json",
       "{\"n\": {\"type\": \"normal\", \"mean\": 1, \"sd\": 0.2},\n \"n\": {\"type\": \"fixed\", \"value\": 1}}",
       "--priors", ":2:2: key 'n': duplicate key (first at line 1, column 2)"},
      {"misspelt field in priors.json", "priors.json", R"({"Kphi": {"type": "uniform", "lower": 0, "uper": 1e7}})",
       "--priors", ": key 'Kphi.uper': unknown key for a uniform prior; expected type, lower, upper"},
      {"a field the prior type does not take", "priors.json", R"({"Kc": {"type": "fixed", "value": 0, "upper": 1}})",
       "--priors", ": key 'Kc.upper': unknown key for a fixed prior; expected type, value"},
      {"one parameter under two names", "priors.json",
       R"({"Kphi": {"type": "uniform", "lower": 0, "upper": 1e7}, "Bekker Kphi": {"type": "fixed", "value": 1e6}})",
       "--priors", ": keys 'Bekker Kphi' and 'Kphi' both give the prior of Kphi; expected one of them"},
      {"1e400 in priors.json", "priors.json", R"({"c": {"type": "uniform", "lower": 0, "upper": 1e400}})", "--priors",
       ":1:48: key 'c.upper': '1e400' is out of range for a double"},
  };
  for (const auto& c : cases) {
    SECTION(c.name) {
      const std::string file = dir + "/" + c.file;
      write_bytes(file, c.bytes);
      const std::string plate_arg = std::string(c.option) == "--plate" ? file : demo_data("plate.csv");
      const std::string priors_arg = std::string(c.option) == "--priors" ? " --priors " + file : "";
      const CliResult r = run_cli("calibrate --plate " + plate_arg + priors_arg + " --out " + out, dir);
      INFO("stderr was: " << r.err);
      CHECK(r.exit_code == 2);
      CHECK(r.err.find(file + c.expect) != std::string::npos);
      CHECK_FALSE(fs::exists(out));
    }
  }
}
