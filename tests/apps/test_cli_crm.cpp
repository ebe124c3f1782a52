// A scene is validated before anything runs; each bad value exits 2 with
// the key, the value and the allowed range. And a short run resumes exactly from its checkpoint.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <functional>

#include <nlohmann/json.hpp>

#include "core/vtu_writer.hpp"
#include "tests/apps/cli_runner.hpp"
#include "tests/highfi/crm/crm_test_scenes.hpp"
#include "tests/scratch_dir.hpp"

using namespace terracal;
using namespace terracal::test;

namespace {
nlohmann::json good_scene() {
  nlohmann::json j = test::bed_scene_json(0.01, 6, 4, 0.0);
  j["duration"] = 0.003;
  j["bodies"] = {{{"name", "plate"},
                  {"shape", {{"type", "disc"}, {"radius", 0.02}, {"thickness", 0.01}}},
                  {"position", {0.03, 0.03, 0.05}},
                  {"motion", {{"type", "prescribed"}, {"linear_velocity", {0, 0, -0.1}}}}}};
  return j;
}
}  // namespace

TEST_CASE("terracal crm: bad scenes exit 2 naming the key, value and range", "[apps][crm]") {
  ScratchDir dir("crm_bad");
  struct Case {
    const char* what;
    std::function<void(nlohmann::json&)> edit;
    std::vector<std::string> expect;
  };
  const std::vector<Case> cases = {
      {"spacing too coarse for the bin",
       [](auto& j) { j["resolution"]["spacing"] = 0.03; },
       {"bin.size", "too coarse"}},
      {"spacing too coarse for the body",
       [](auto& j) { j["bodies"][0]["shape"]["radius"] = 0.015; },
       {"shape.radius", "too coarse"}},
      {"h/d0 out of range", [](auto& j) { j["resolution"]["h_over_d0"] = 2.0; }, {"h_over_d0", "2", "[1, 1.6]"}},
      {"marker velocity not a known rule",
       [](auto& j) { j["resolution"]["marker_velocity"] = "slip"; },
       {"marker_velocity", "slip", "mirror"}},
      {"step above CFL", [](auto& j) { j["resolution"]["time_step"] = 1e-3; }, {"time_step", "0.001", "CFL"}},
      {"nu >= 0.5", [](auto& j) { j["soil"]["poisson_ratio"] = 0.5; }, {"poisson_ratio", "0.5", "[0, 0.5)"}},
      {"non-positive density", [](auto& j) { j["soil"]["density"] = 0; }, {"density", "0", "(0,"}},
      {"non-positive modulus", [](auto& j) { j["soil"]["young_modulus"] = -1e6; }, {"young_modulus", "-1000000"}},
      {"body outside the bin",
       [](auto& j) {
         j["bodies"][0]["position"] = {0.5, 0.03, 0.05};
       },
       {"position", "outside the bin"}},
      {"unknown key", [](auto& j) { j["resolution"]["spacnig"] = 0.01; }, {"resolution.spacnig", "unknown key"}},
      {"unknown effect", [](auto& j) { j["effects"] = {"bulldozing"}; }, {"effects", "bulldozing", "active_domain"}},
      {"cohesion without its effect", [](auto& j) { j["soil"]["cohesion"] = 5000; }, {"soil.cohesion", "\"cohesion\""}},
  };
  for (const Case& c : cases) {
    INFO(c.what);
    nlohmann::json j = good_scene();
    c.edit(j);
    const std::string scene = dir.path.string() + "/scene.json";
    test::write(scene, j.dump());
    const CliResult r =
        test::run_cli("crm --scene " + scene + " --out " + dir.path.string() + "/out --cache ''", dir.path);
    INFO(r.err);
    CHECK(r.exit_code == 2);
    for (const auto& e : c.expect) CHECK(r.err.find(e) != std::string::npos);
    CHECK(!std::filesystem::exists(dir.path.string() + "/out/bodies.csv"));
  }
}

TEST_CASE("terracal crm: a resumed run ends with exactly the files of an uninterrupted one", "[apps][crm]") {
  ScratchDir dir("crm_resume");
  nlohmann::json j = good_scene();
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
