#pragma once
// Where the tests find the program, the source tree and the reference tables. The build compiles its
// own paths in; a test binary run elsewhere (a bundle copied to a GPU machine, run from a copy of the
// working tree) takes TERRACAL_EXE / TERRACAL_SOURCE_DIR / TERRACAL_REFERENCE_DIR from the
// environment, else the terracal beside the test binary, the working directory and its data/reference.
#include <cstdlib>
#include <filesystem>
#include <string>

namespace terracal::test {

namespace detail {
inline std::string first_existing(const char* env, const std::string& compiled, const std::string& fallback) {
  if (const char* e = std::getenv(env); e && *e) return e;
  std::error_code ignored;
  return std::filesystem::exists(compiled, ignored) ? compiled : fallback;
}
}  // namespace detail

inline const std::string& terracal_exe() {
  static const std::string exe = detail::first_existing(
      "TERRACAL_EXE", TERRACAL_EXE, (std::filesystem::read_symlink("/proc/self/exe").parent_path() / "terracal").string());
  return exe;
}

inline const std::string& source_dir() {
  static const std::string dir =
      detail::first_existing("TERRACAL_SOURCE_DIR", TERRACAL_SOURCE_DIR, std::filesystem::current_path().string());
  return dir;
}

inline const std::string& reference_dir() {
  static const std::string dir =
      detail::first_existing("TERRACAL_REFERENCE_DIR", TERRACAL_REFERENCE_DIR, source_dir() + "/data/reference");
  return dir;
}

}  // namespace terracal::test
