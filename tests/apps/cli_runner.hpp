#pragma once
// Runs the terracal executable as a child process for the command-line tests.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "../scratch_dir.hpp"
#include "../test_paths.hpp"

namespace terracal::test {

struct CliResult {
  int exit_code = -1;
  std::string out, err;
};

inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

inline CliResult run_cli(const std::string& args, const std::string& scratch) {
  const std::string out = scratch + "/stdout.txt", err = scratch + "/stderr.txt";
  const std::string cmd = terracal_exe() + " " + args + " > " + out + " 2> " + err + " < /dev/null";
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read_file(out);
  r.err = read_file(err);
  return r;
}

inline void write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

inline std::string demo_data(const std::string& file) { return source_dir() + "/studies/demo/" + file; }

}  // namespace terracal::test
