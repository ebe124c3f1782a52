// Bad command lines, whatever the command: unknown commands and options. And --help and --version,
// the two ways to ask for text instead of a run, exit 0.
#include "bad_input_suite.hpp"

using terracal::test::BadInput;

TEST_CASE("bad input, command line: unknown commands and options", "[cli][bad_input]") {
  const std::vector<BadInput> cases = {
      {"unknown command",
       {},
       "frobnicate",
       {"terracal: unknown command 'frobnicate'; expected one of calibrate, demo, synthesize, crm, bevameter, wheel, wheel-table, "
        "pipeline"}},
      {"misspelt command", {}, "calibrte --plate x.csv", {"unknown command 'calibrte' (did you mean 'calibrate'?)"}},
      {"no command", {}, "", {"terracal: a command is required; expected one of calibrate, demo,"}},
      {"unknown option before the command", {}, "--frobnicate", {"terracal: unknown option '--frobnicate'"}},
      {"misspelt option",
       {},
       "calibrate --plat x.csv --out {out}",
       {"terracal calibrate: unknown option '--plat' (did you mean '--plate'?)",
        "'terracal calibrate --help' lists the options"}},
      {"misspelt option with =",
       {},
       "calibrate --plate=x.csv --sed=3 --out {out}",
       {"unknown option '--sed' (did you mean '--seed'?)"}},
      {"unknown option",
       {},
       "calibrate --frobnicate 3 --out {out}",
       {"terracal calibrate: unknown option '--frobnicate';"}},
  };
  terracal::test::check_bad_inputs("bad_cmdline", cases);
}

TEST_CASE("every command's --help, and --version, exit 0", "[cli]") {
  const terracal::test::ScratchDir scratch("help");
  const std::string dir = scratch.str();
  auto r = terracal::test::run_cli("--version", dir);
  CHECK(r.exit_code == 0);
  CHECK(r.out.find("terracal ") == 0);
  for (const char* command : {"calibrate", "synthesize", "crm", "bevameter", "wheel", "pipeline", "demo"}) {
    r = terracal::test::run_cli(std::string(command) + " --help", dir);
    INFO(command);
    CHECK(r.exit_code == 0);
    CHECK(r.out.find("--out") != std::string::npos);
  }
}
