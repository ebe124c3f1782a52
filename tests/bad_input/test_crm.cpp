// Bad input to `terracal crm`: the scene (its keys, bodies and OBJ meshes) and the options. Every
// case is refused while the scene is read, before a particle is made.
#include <functional>

#include <nlohmann/json.hpp>

#include "bad_input_suite.hpp"
#include "tests/highfi/crm/crm_test_scenes.hpp"

using namespace std::string_literals;
using terracal::test::BadInput;
using terracal::test::InputFile;

namespace {

// The small plate scene (tests/highfi/crm/crm_test_scenes.hpp) with one edit, run.
BadInput scene(const std::string& name, const std::function<void(nlohmann::json&)>& edit,
               std::vector<std::string> phrases, std::vector<InputFile> more = {}) {
  nlohmann::json j = terracal::test::plate_scene_json();
  edit(j);
  more.push_back({"scene.json", j.dump()});
  return {name, std::move(more), "crm --scene {dir}/scene.json --out {out} --cache ''", std::move(phrases)};
}

// The good scene whose body is the mesh of an OBJ file with the given text.
BadInput mesh(const std::string& name, const std::string& obj, std::vector<std::string> phrases) {
  return scene(name,
               [](auto& j) {
                 j["bodies"][0]["shape"] = {{"type", "mesh"}, {"file", "body.obj"}};
               },
               std::move(phrases), {{"body.obj", obj}});
}

const std::string kCube = "v 0 0 0\nv 0.02 0 0\nv 0 0.02 0\nv 0 0 0.02\n";

}  // namespace

TEST_CASE("bad input, crm: the scene", "[cli][bad_input]") {
  const std::vector<BadInput> cases = {
      scene("spacing too coarse for the bin", [](auto& j) { j["resolution"]["spacing"] = 0.03; },
            {"bin.size", "too coarse"}),
      scene("spacing too coarse for the body", [](auto& j) { j["bodies"][0]["shape"]["radius"] = 0.015; },
            {"shape.radius", "too coarse"}),
      scene("lost fraction above 1",
            [](auto& j) {
              j["checks"] = {{"max_lost_fraction", 2}};
            },
            {"checks.max_lost_fraction", "2", "[0, 1]"}),
      scene("unknown key in checks",
            [](auto& j) {
              j["checks"] = {{"max_lost", 0.1}};
            },
            {"checks.max_lost"}),
      scene("h/d0 out of range", [](auto& j) { j["resolution"]["h_over_d0"] = 2.0; }, {"h_over_d0", "2", "[1, 1.6]"}),
      scene("marker velocity not a known rule", [](auto& j) { j["resolution"]["marker_velocity"] = "slip"; },
            {"marker_velocity", "slip", "mirror"}),
      scene("negative wall contact", [](auto& j) { j["resolution"]["wall_contact"] = -1; },
            {"resolution.wall_contact", "-1", "[0, 100]"}),
      scene("sort skin too wide", [](auto& j) { j["resolution"]["sort_skin"] = 0.8; },
            {"resolution.sort_skin", "0.8", "[0, 0.5]"}),
      scene("step above CFL", [](auto& j) { j["resolution"]["time_step"] = 1e-3; }, {"time_step", "0.001", "CFL"}),
      scene("nu >= 0.5", [](auto& j) { j["soil"]["poisson_ratio"] = 0.5; }, {"poisson_ratio", "0.5", "[0, 0.5)"}),
      scene("non-positive density", [](auto& j) { j["soil"]["density"] = 0; }, {"density", "0", "(0,"}),
      scene("non-positive modulus", [](auto& j) { j["soil"]["young_modulus"] = -1e6; }, {"young_modulus", "-1000000"}),
      scene("gravity pointing up",
            [](auto& j) {
              j["soil"]["gravity"] = {0, 0, 9.81};
            },
            {"key 'soil.gravity': [0, 0, 9.81] m/s^2 does not point down"}),
      scene("body outside the bin",
            [](auto& j) {
              j["bodies"][0]["position"] = {0.5, 0.03, 0.05};
            },
            {"position", "outside the bin"}),
      scene("negative inertia",
            [](auto& j) {
              j["bodies"][0]["motion"] = {{"type", "dynamic"}};
              j["bodies"][0]["mass"] = 1;
              j["bodies"][0]["inertia"] = {1e-3, -1e-3, 1e-3};
            },
            {"key 'bodies[0].inertia': principal moments must not be negative"}),
      scene("a seed beyond the long range (it wrapped to a negative number)",
            [](auto& j) { j["settle_seed"] = 18446744073709551615ULL; },
            {"key 'settle_seed': value 18446744073709551615 is outside the allowed range [0, "}),
      scene("unknown key", [](auto& j) { j["resolution"]["spacnig"] = 0.01; }, {"resolution.spacnig", "unknown key"}),
      scene("unknown effect", [](auto& j) { j["effects"] = {"bulldozing"}; },
            {"effects", "bulldozing", "active_domain"}),
      scene("cohesion without its effect", [](auto& j) { j["soil"]["cohesion"] = 5000; },
            {"soil.cohesion", "\"cohesion\""}),
      // A resolution that cannot fit in memory: refused before anything is allocated.
      scene("spacing beyond memory",
            [](auto& j) {
              j["bin"] = {{"size", {0.3, 0.3, 0.2}}, {"fill_height", 0.12}};
              j["resolution"]["spacing"] = 1e-4;
            },
            {"scene.json: key 'resolution.spacing' 0.0001 m: a CRM bin", "GiB of memory where", "is available",
             "expected a coarser resolution.spacing"}),
      {"not JSON",
       {{"scene.json", "{\"soil\": {\n\"density\": 1700,,}}"}},
       "crm --scene {dir}/scene.json --out {out}",
       {"{dir}/scene.json:2", "not valid JSON"}},
  };
  terracal::test::check_bad_inputs("bad_crm_scene", cases);
}

TEST_CASE("bad input, crm: OBJ meshes", "[cli][bad_input]") {
  const std::vector<BadInput> cases = {
      mesh("a coordinate that is not a number", kCube + "v 0 zero 0\nf 1 2 3\n",
           {"{dir}/body.obj:5: 'zero' is not a finite coordinate"}),
      mesh("a vertex with two coordinates", kCube + "v 0 0\nf 1 2 3\n",
           {"{dir}/body.obj:5: a vertex needs 3 coordinates"}),
      mesh("a face with a word", kCube + "f 1 2 x\n", {"{dir}/body.obj:5: 'x' is not a vertex number"}),
      mesh("a face of two vertices", kCube + "f 1 2\n", {"{dir}/body.obj:5: a face needs 3 vertices"}),
      mesh("vertex 0", kCube + "f 0 1 2\n", {"{dir}/body.obj:5: 0 is not a vertex number"}),
      mesh("a relative vertex before the first", kCube + "f -1 -2 -9\n",
           {"{dir}/body.obj:5: -9 is not a vertex number"}),
      mesh("a vertex beyond the last", kCube + "f 1 2 3\nf 1 2 9\n",
           {"{dir}/body.obj:6: a face refers to vertex 9; expected 1 to 4"}),
      mesh("no faces", kCube, {"has no faces"}),
      mesh("UTF-16",
           "\xFF\xFE"
           "v\0 \0"
           "0\0"s,
           {"{dir}/body.obj:1:1: found bytes FF FE"}),
      scene("a mesh file that does not exist",
            [](auto& j) {
              j["bodies"][0]["shape"] = {{"type", "mesh"}, {"file", "none.obj"}};
            },
            {"none.obj"}),
  };
  terracal::test::check_bad_inputs("bad_crm_obj", cases);
}

TEST_CASE("bad input, crm: options", "[cli][bad_input]") {
  const std::vector<BadInput> cases = {
      {"--record-every -5",
       {{"scene.json", terracal::test::plate_scene_json().dump()}},
       "crm --scene {dir}/scene.json --out {out} --record-every -5",
       {"--record-every: value -5 is outside [1, 1099511627776]"}},
      {"--resume without a checkpoint",
       {{"scene.json", terracal::test::plate_scene_json().dump()}},
       "crm --scene {dir}/scene.json --resume --out {out}",
       {"--resume: {dir}/out/checkpoint.h5 does not exist"}},
      {"--out is a file",
       {{"scene.json", terracal::test::plate_scene_json().dump()}, {"afile", "x\n"}},
       "crm --scene {dir}/scene.json --out {dir}/afile",
       {"--out {dir}/afile: exists and is not a folder"}},
  };
  terracal::test::check_bad_inputs("bad_crm_opt", cases);
}
