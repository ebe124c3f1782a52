#pragma once
// The bad-input suite: for each command and each kind of input it reads, a table of cases
// (the files to write and the command line -> the exit code and phrases of the message). Every
// case runs the real program and checks that it refuses with exit 2 (or, where the contract says
// so, another code), that stderr names what was wrong, and that no output folder was left behind.
// One file per command (test_<command>.cpp); a new command or input kind adds a table there.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../apps/cli_runner.hpp"
#include "tests/test_paths.hpp"

namespace terracal::test {

struct InputFile {
  std::string name;   // in the case's scratch folder
  std::string bytes;  // written as they are (NUL bytes, BOMs and all)
};

struct BadInput {
  std::string name;                  // what is wrong, in words
  std::vector<InputFile> files;      // written before the command runs
  std::string args;                  // {dir}: the scratch folder; {out}: {dir}/out; see expand()
  std::vector<std::string> phrases;  // each must appear in stderr ({dir} and {demo} are replaced here too)
  int exit_code = 2;
};

// The placeholders of args and phrases: {out} ({dir}/out), {dir} (the case's scratch folder), {demo}
// (the demo's data set: plate.csv, shear.csv, truth.json) and {soil} (a CRM soil of the pipeline study).
inline std::string expand(std::string text, const std::string& dir) {
  const std::string studies = terracal::test::source_dir() + "/studies";
  const std::pair<std::string, std::string> names[] = {{"{out}", dir + "/out"},
                                                       {"{dir}", dir},
                                                       {"{demo}", studies + "/demo"},
                                                       {"{soil}", studies + "/pipeline/bevameter_soil_2022.json"}};
  for (const auto& [key, value] : names)
    for (auto at = text.find(key); at != std::string::npos; at = text.find(key, at + value.size()))
      text.replace(at, key.size(), value);
  return text;
}

// The names in a folder, sorted.
inline std::vector<std::string> names_in(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// Runs every case in a fresh scratch folder of its own, with the files of `common` (inputs that
// many cases name) and the case's own files written into it first.
inline void check_bad_inputs(const std::string& tag, const std::vector<BadInput>& cases,
                             const std::vector<InputFile>& common = {}) {
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const BadInput& c = cases[i];
    const ScratchDir scratch(tag + "_" + std::to_string(i));
    const std::string dir = scratch.str();
    for (const auto* files : {&common, &c.files})
      for (const auto& f : *files) std::ofstream(dir + "/" + f.name, std::ios::binary) << f.bytes;
    std::vector<std::string> before = names_in(dir);
    for (const char* log : {"stderr.txt", "stdout.txt"}) before.push_back(log);
    std::sort(before.begin(), before.end());
    const CliResult r = run_cli(expand(c.args, dir), dir);
    INFO(c.name << "\n  terracal " << expand(c.args, dir) << "\n  stderr: " << r.err);
    CHECK(r.exit_code == c.exit_code);
    for (const auto& p : c.phrases) CHECK(r.err.find(expand(p, dir)) != std::string::npos);
    // Nothing left behind by a refused run: no output folder (nor the folders above it), no file.
    if (c.exit_code == 2) CHECK(names_in(dir) == before);
  }
}

}  // namespace terracal::test
