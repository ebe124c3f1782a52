#pragma once
// The bad-input suite: for each command and each kind of input it reads, a table of cases
// (the files to write and the command line -> the exit code and phrases of the message). Every
// case runs the real program and checks that it refuses with exit 2 (or, where the contract says
// so, another code), that stderr names what was wrong, and that no output folder was left behind.
// One file per command (test_<command>.cpp); a new command or input kind adds a table there.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../apps/cli_runner.hpp"

namespace terracal::test {

struct InputFile {
  std::string name;   // in the case's scratch folder
  std::string bytes;  // written as they are (NUL bytes, BOMs and all)
};

struct BadInput {
  std::string name;                  // what is wrong, in words
  std::vector<InputFile> files;      // written before the command runs
  std::string args;                  // {dir}: the scratch folder; {out}: {dir}/out; {demo}: studies/demo
  std::vector<std::string> phrases;  // each must appear in stderr ({dir} and {demo} are replaced here too)
  int exit_code = 2;
};

inline std::string expand(std::string text, const std::string& dir) {
  const std::pair<std::string, std::string> names[] = {
      {"{out}", dir + "/out"}, {"{dir}", dir}, {"{demo}", std::string(TERRACAL_SOURCE_DIR) + "/studies/demo"}};
  for (const auto& [key, value] : names)
    for (auto at = text.find(key); at != std::string::npos; at = text.find(key, at + value.size()))
      text.replace(at, key.size(), value);
  return text;
}

// Runs every case in a fresh scratch folder of its own.
inline void check_bad_inputs(const std::string& tag, const std::vector<BadInput>& cases) {
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const BadInput& c = cases[i];
    const ScratchDir scratch(tag + "_" + std::to_string(i));
    const std::string dir = scratch.str();
    for (const auto& f : c.files) std::ofstream(dir + "/" + f.name, std::ios::binary) << f.bytes;
    const CliResult r = run_cli(expand(c.args, dir), dir);
    INFO(c.name << "\n  terracal " << expand(c.args, dir) << "\n  stderr: " << r.err);
    CHECK(r.exit_code == c.exit_code);
    for (const auto& p : c.phrases) CHECK(r.err.find(expand(p, dir)) != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(dir + "/out"));  // no output folder left by a refused run
  }
}

}  // namespace terracal::test
