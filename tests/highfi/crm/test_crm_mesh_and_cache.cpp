// The triangle-mesh shape and the settled-bed cache.
// - A box given as an OBJ mesh gets the same markers as the built-in box, so pushing either into
//   the bed gives the same force: the mesh path (OBJ reader, signed distance by ray parity) agrees
//   with the analytic shape.
// - A settled bed is cached per soil, bin, spacing and numerics: the second request reads the
//   first's bed back exactly, and a different soil is settled anew.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "highfi/crm/body_markers.hpp"
#include "highfi/crm/crm_run.hpp"
#include "highfi/crm/crm_solver.hpp"
#include "tests/highfi/crm/crm_test_scenes.hpp"

using namespace terracal;
namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("terracal_test_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

// A cube of half-size a as an OBJ file with quad faces (fanned into triangles by the reader).
fs::path write_cube_obj(const fs::path& dir, double a) {
  const fs::path f = dir / "cube.obj";
  std::ofstream o(f);
  o << "# cube\n";
  for (int k = 0; k < 8; ++k)
    o << "v " << ((k & 1) ? a : -a) << ' ' << ((k & 2) ? a : -a) << ' ' << ((k & 4) ? a : -a) << '\n';
  o << "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
  return f;
}

double pushed_force(const nlohmann::json& shape) {
  nlohmann::json j = test::bed_scene_json(0.01, 14, 8, 0.0);
  j["resolution"]["cpu_precision"] = "float";
  j["bodies"] = {{{"name", "block"},
                  {"shape", shape},
                  {"position", {0.07, 0.07, 0.08 + 0.03}},
                  {"motion", {{"type", "prescribed"}, {"linear_velocity", {0, 0, -0.2}}}}}};
  CrmSolver s(test::scene_from(j), CrmDevice::kCpu);
  for (int k = 0; k < 150; ++k) s.step();
  return s.wrenches()[0].force.z;
}

}  // namespace

TEST_CASE("CRM: a box given as an OBJ mesh acts like the built-in box", "[highfi][crm]") {
  const fs::path dir = fresh_dir("mesh");
  const fs::path obj = write_cube_obj(dir, 0.03);
  const CrmScene sc = test::scene_from([&] {
    nlohmann::json j = test::bed_scene_json(0.01, 14, 8);
    j["bodies"] = {
        {{"name", "m"}, {"shape", {{"type", "mesh"}, {"file", obj.string()}}}, {"position", {0.07, 0.07, 0.15}}}};
    return j;
  }());
  BodyShape box;
  box.type = ShapeType::kBox;
  box.half_extents = {0.03, 0.03, 0.03};
  // Signed distance: inside, on a face's normal, and beyond a corner.
  for (const Vec3<double> p : {Vec3<double>{0, 0, 0}, Vec3<double>{0.01, -0.02, 0.005}, Vec3<double>{0.05, 0.0, 0.0},
                               Vec3<double>{0.04, 0.05, -0.06}})
    CHECK(shape_signed_distance(sc.bodies[0].shape, p) == Approx(shape_signed_distance(box, p)).margin(1e-12));
  const auto mesh_markers = body_marker_positions(sc.bodies[0].shape, 0.01, 3);
  const auto box_markers = body_marker_positions(box, 0.01, 3);
  CHECK(mesh_markers.size() == box_markers.size());
  CHECK(mesh_markers.size() > 100);

  const double f_mesh = pushed_force({{"type", "mesh"}, {"file", obj.string()}});
  const double f_box = pushed_force({{"type", "box"}, {"size", {0.06, 0.06, 0.06}}});
  std::printf("block pushed 3 cm deep: mesh %.4f N, box %.4f N\n", f_mesh, f_box);
  CHECK(f_box > 1.0);
  CHECK(f_mesh == Approx(f_box).epsilon(1e-4));
  fs::remove_all(dir);
}

TEST_CASE("CRM: a settled bed is cached per soil and read back exactly", "[highfi][crm]") {
  const fs::path cache = fresh_dir("bed_cache");
  nlohmann::json j = test::bed_scene_json(0.02, 8, 5, 0.02);
  const CrmScene sc = test::scene_from(j);
  bool cached = true;
  const HostSoil first = settled_bed(sc, CrmDevice::kCpu, cache, &cached);
  CHECK_FALSE(cached);
  CHECK(std::distance(fs::directory_iterator(cache), fs::directory_iterator{}) == 1);
  const HostSoil again = settled_bed(sc, CrmDevice::kCpu, cache, &cached);
  CHECK(cached);
  REQUIRE(again.size() == first.size());
  bool same = true;
  for (std::size_t i = 0; i < first.size(); ++i)
    same = same && first.pos[i].x == again.pos[i].x && first.pos[i].z == again.pos[i].z &&
           first.s0[i].z == again.s0[i].z && first.ids[i] == again.ids[i];
  CHECK(same);
  // Settling changed the bed: the cache holds a settled state, not the initial lattice.
  const HostSoil lattice = initial_bed(sc);
  double moved = 0;
  for (std::size_t i = 0; i < first.size(); ++i)
    moved = std::max(moved, std::abs(first.s0[i].z - lattice.s0[std::size_t(first.ids[i])].z));
  CHECK(moved > 0);
  // Another soil is another bed.
  j["soil"]["mu_s"] = 0.6;
  j["soil"]["mu_2"] = 0.6;
  settled_bed(test::scene_from(j), CrmDevice::kCpu, cache, &cached);
  CHECK_FALSE(cached);
  CHECK(std::distance(fs::directory_iterator(cache), fs::directory_iterator{}) == 2);
  fs::remove_all(cache);
}
