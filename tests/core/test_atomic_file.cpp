#include <catch2/catch.hpp>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"

namespace fs = std::filesystem;

namespace {
std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
}  // namespace

TEST_CASE("atomic_file: temporary name is hidden, per process, in the same folder", "[core][atomic_file]") {
  const std::string tmp = terracal::temporary_path_for("/some/dir/out.csv");
  CHECK(tmp == "/some/dir/.out.csv.tmp." + std::to_string(::getpid()));
  CHECK(terracal::temporary_path_for("out.csv") == ".out.csv.tmp." + std::to_string(::getpid()));
  CHECK_THROWS_AS(terracal::temporary_path_for("/some/dir/"), terracal::RunError);
}

TEST_CASE("atomic_file: write replaces the file whole, a failure leaves nothing", "[core][atomic_file]") {
  const fs::path dir = fs::temp_directory_path() / ("terracal_test_atomic_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path file = dir / "summary.txt";

  terracal::write_text_atomically(file.string(), "first\n");
  CHECK(slurp(file) == "first\n");
  terracal::write_text_atomically(file.string(), "second, longer\n");
  CHECK(slurp(file) == "second, longer\n");

  const fs::path missing = dir / "nope" / "x.txt";
  CHECK_THROWS_AS(terracal::write_text_atomically(missing.string(), "x"), terracal::RunError);
  CHECK_FALSE(fs::exists(missing.parent_path()));

  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++entries;
  CHECK(entries == 1);  // no temporaries left behind
  fs::remove_all(dir);
}
