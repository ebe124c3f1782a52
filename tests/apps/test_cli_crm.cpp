// terracal crm: a short run resumes exactly from its checkpoint (bad scenes: tests/bad_input/test_crm.cpp).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "core/vtu_writer.hpp"
#include "tests/apps/cli_runner.hpp"
#include "tests/highfi/crm/crm_test_scenes.hpp"
#include "tests/scratch_dir.hpp"

using namespace terracal;
using namespace terracal::test;

TEST_CASE("terracal crm: a resumed run ends with exactly the files of an uninterrupted one", "[apps][crm]") {
  ScratchDir dir("crm_resume");
  nlohmann::json j = terracal::test::plate_scene_json();
  j["duration"] = 0.006;
  j["output"] = {{"vtu_every", 3}};  // snapshots before and after the checkpoint: one collection
  const std::string full = dir.path.string() + "/full.json", half = dir.path.string() + "/half.json";
  test::write(full, j.dump());
  const CliResult a =
      test::run_cli("crm --scene " + full + " --out " + dir.path.string() + "/a --cache '' --record-every 1", dir.path);
  REQUIRE(a.exit_code == 0);
  // The same scene stopped half-way (its checkpoint), then resumed with the full duration.
  j["duration"] = 0.003;
  test::write(half, j.dump());
  REQUIRE(
      test::run_cli("crm --scene " + half + " --out " + dir.path.string() + "/b --cache '' --record-every 1", dir.path)
          .exit_code == 0);
  // A copy of the half-way folder with one byte of its checkpoint flipped.
  const std::string root = dir.path.string();
  std::filesystem::copy(root + "/b", root + "/c", std::filesystem::copy_options::recursive);
  std::string bytes = test::read_file(root + "/c/checkpoint.h5");
  bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x01);
  std::ofstream(root + "/c/checkpoint.h5", std::ios::binary) << bytes;

  const CliResult b =
      test::run_cli("crm --scene " + full + " --out " + root + "/b --cache '' --record-every 1 --resume", dir.path);
  INFO(b.err);
  REQUIRE(b.exit_code == 0);
  CHECK(b.err.find("resuming from " + root + "/b/checkpoint.h5") != std::string::npos);
  CHECK(test::read_file(root + "/a/bodies.csv") == test::read_file(root + "/b/bodies.csv"));
  CHECK(test::read_file(root + "/a/bodies.csv").size() > 100);
  CHECK(test::read_file(root + "/a/soil.pvd") == test::read_file(root + "/b/soil.pvd"));
  CHECK(terracal::read_pvd(root + "/a/soil.pvd").size() >= 3);
  // The damaged checkpoint is named, the run starts over, and ends as the uninterrupted one.
  const CliResult c =
      test::run_cli("crm --scene " + full + " --out " + root + "/c --cache '' --record-every 1 --resume", dir.path);
  INFO(c.err);
  REQUIRE(c.exit_code == 0);
  CHECK(c.err.find(root + "/c/checkpoint.h5 cannot be resumed") != std::string::npos);
  CHECK(c.err.find("the run starts from the beginning") != std::string::npos);
  CHECK(test::read_file(root + "/a/bodies.csv") == test::read_file(root + "/c/bodies.csv"));
}

TEST_CASE("terracal crm: snapshots start at output.vtu_from", "[apps][crm]") {
  ScratchDir dir("crm_vtu_from");
  nlohmann::json j = terracal::test::plate_scene_json();
  j["duration"] = 0.006;
  j["output"] = {{"vtu_every", 2}, {"vtu_from", 0.003}};
  const std::string scene = dir.path.string() + "/scene.json";
  test::write(scene, j.dump());
  const CliResult r = test::run_cli("crm --scene " + scene + " --out " + dir.path.string() + "/o --cache ''", dir.path);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto snaps = terracal::read_pvd(dir.path.string() + "/o/soil.pvd");
  REQUIRE(snaps.size() >= 2);
  for (const auto& s : snaps) CHECK(s.first >= 0.003);
  // Every snapshot from 0.003 s on is there: none more than two steps after that time.
  CHECK(snaps.front().first < 0.003 + 2 * (snaps[1].first - snaps[0].first));
}
