#pragma once
// A fresh folder under the system temporary folder for one test, removed when the test ends --
// also when it fails. TERRACAL_KEEP_TEST_FILES=1 keeps it (to look at plots or outputs by eye).
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace terracal::test {

struct ScratchDir {
  std::filesystem::path path;
  explicit ScratchDir(const std::string& tag)
      : path(std::filesystem::temp_directory_path() / ("terracal_test_" + tag + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~ScratchDir() {
    const char* keep = std::getenv("TERRACAL_KEEP_TEST_FILES");
    std::error_code ignored;
    if (!keep || std::string(keep) != "1") std::filesystem::remove_all(path, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  std::string str() const { return path.string(); }
};

}  // namespace terracal::test
