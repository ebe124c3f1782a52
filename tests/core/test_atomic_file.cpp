#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

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

TEST_CASE("atomic_file: the temporaries of writers that died are removed, no other file", "[core][atomic_file]") {
  const fs::path dir = fs::temp_directory_path() / ("terracal_test_stale_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const pid_t gone = fork();  // a process that has ended: its PID names no running writer
  if (gone == 0) _exit(0);
  waitpid(gone, nullptr, 0);
  const std::string dead = ".summary.txt.tmp." + std::to_string(gone);
  const std::string mine = ".summary.txt.tmp." + std::to_string(::getpid());  // a write in progress
  for (const std::string& name :
       {dead, mine, std::string(".notes.tmp.abc"), std::string("summary.txt"), std::string("result.tmp.1")})
    std::ofstream(dir / name) << "x";
  const std::vector<std::string> removed = terracal::remove_stale_temporaries(dir.string());
  CHECK(removed == std::vector<std::string>{dead});
  CHECK_FALSE(fs::exists(dir / dead));
  for (const char* kept : {".notes.tmp.abc", "summary.txt", "result.tmp.1"}) CHECK(fs::exists(dir / kept));
  CHECK(fs::exists(dir / mine));
  fs::remove_all(dir);
}
