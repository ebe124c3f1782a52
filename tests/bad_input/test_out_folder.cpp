// --out, which every command takes: a path that cannot be a folder exits 2 naming --out before any
// work, and a refused run leaves no folder behind (apps/out_dir.hpp).
#include <unistd.h>

#include "apps/out_dir.hpp"
#include "bad_input_suite.hpp"
#include "core/errors.hpp"
#include "tests/skip.hpp"

using terracal::test::BadInput;
namespace fs = std::filesystem;

TEST_CASE("bad input, --out", "[cli][bad_input]") {
  const std::string synth = "synthesize --truth {demo}/truth.json --out ";
  const std::vector<BadInput> cases = {
      {"under /proc",
       {},
       synth + "/proc/terracal_no_such_folder/out",
       {"--out /proc/terracal_no_such_folder/out: cannot make the folder"}},
      {"under a file", {{"afile", "x\n"}}, synth + "{dir}/afile/out", {"--out {dir}/afile/out:", "is not a folder"}},
      {"empty", {}, synth + "''", {"--out '': an empty path"}},
      // The folders a refused run would have made above --out are not left behind either.
      {"refused after the path was checked",
       {},
       "calibrate --plate {dir}/none.csv --out {dir}/made/out",
       {"{dir}/none.csv"}},
  };
  terracal::test::check_bad_inputs("bad_out", cases);
}

TEST_CASE("an --out in a folder without write permission: exit 2 naming --out", "[cli][bad_input]") {
  if (::geteuid() == 0) {
    terracal::test::report_skip("--out without write permission", "running as root, who writes in any folder");
    return;
  }
  const terracal::test::ScratchDir scratch("bad_out_ro");
  const std::string d = scratch.str();
  fs::create_directories(d + "/locked");
  fs::permissions(d + "/locked", fs::perms::owner_read | fs::perms::owner_exec);
  const auto r = terracal::test::run_cli(
      "synthesize --truth " + terracal::test::demo_data("truth.json") + " --out " + d + "/locked/out", d);
  fs::permissions(d + "/locked", fs::perms::owner_all);
  INFO(r.err);
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("--out " + d + "/locked/out: cannot make the folder") != std::string::npos);
  CHECK_FALSE(fs::exists(d + "/locked/out"));
}

TEST_CASE("OutDir removes the empty folders a failed run made, and nothing else", "[cli][bad_input]") {
  using terracal::InputError;
  const terracal::test::ScratchDir scratch("bad_out_dir");
  const std::string d = scratch.str();
  auto fail_in = [](const std::string& path, bool write_output) {
    try {
      const terracal::app::OutDir out = terracal::app::prepare_out_dir("--out", path);
      fs::create_directories(path);
      if (write_output) terracal::test::write(path + "/plate.csv", "plate_radius_m,sinkage_m,force_N\n");
      throw InputError("refused after the folder was made");
    } catch (const InputError&) {
    }
  };
  fail_in(d + "/a/b", false);
  CHECK_FALSE(fs::exists(d + "/a"));  // both folders it made, innermost first
  fail_in(d + "/c/d", true);
  CHECK(fs::exists(d + "/c/d/plate.csv"));  // outputs are never removed
  fs::create_directories(d + "/e");
  fail_in(d + "/e", false);
  CHECK(fs::exists(d + "/e"));  // a folder that was there before stays
  {
    const terracal::app::OutDir out = terracal::app::prepare_out_dir("--out", d + "/f");
    fs::create_directories(d + "/f");
  }
  CHECK(fs::exists(d + "/f"));  // a run that ends normally keeps its folder
  CHECK_THROWS_AS(terracal::app::prepare_out_dir("--out", d + "/c/d/plate.csv"), InputError);
}
