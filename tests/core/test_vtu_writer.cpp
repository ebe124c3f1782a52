#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "core/vtu_writer.hpp"
#include "tests/scratch_dir.hpp"
#include "tests/vtu_payload.hpp"

namespace fs = std::filesystem;
using terracal::VtuPointData;
using terracal::test::array_payload;
using terracal::test::slurp;

namespace {

std::size_t entries_in(const fs::path& dir) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
  return n;
}

}  // namespace

TEST_CASE("vtu_writer: a small cloud round-trips through the base64 arrays", "[core][vtu]") {
  terracal::test::ScratchDir dir("vtu_small");
  const fs::path file = dir.path / "cloud.vtu";
  const std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.1, -2.5, 1e3};
  std::vector<VtuPointData> fields = {
      {"density", 1, {1000.f, 1001.5f, 999.25f, -1.f, 3.0e-7f}},
      {"velocity", 3, std::vector<float>(15)},
      {"stress", 6, std::vector<float>(30)},
  };
  for (std::size_t i = 0; i < 15; ++i) fields[1].values[i] = 0.5f * static_cast<float>(i);
  for (std::size_t i = 0; i < 30; ++i) fields[2].values[i] = -static_cast<float>(i) / 7.f;

  terracal::write_vtu_points(file, xyz, fields, 0.125);
  const std::string xml = slurp(file);
  CHECK(xml.rfind("<?xml", 0) == 0);
  CHECK(xml.find("type=\"UnstructuredGrid\"") != std::string::npos);
  CHECK(xml.find("header_type=\"UInt32\"") != std::string::npos);
  CHECK(xml.find("byte_order=\"LittleEndian\"") != std::string::npos);
  CHECK(xml.find("NumberOfPoints=\"5\" NumberOfCells=\"5\"") != std::string::npos);
  CHECK(xml.find("Name=\"density\" NumberOfComponents=\"1\"") != std::string::npos);
  CHECK(xml.find("Name=\"velocity\" NumberOfComponents=\"3\"") != std::string::npos);
  CHECK(xml.find("Name=\"stress\" NumberOfComponents=\"6\"") != std::string::npos);
  CHECK(xml.find("Name=\"TimeValue\"") != std::string::npos);
  CHECK(xml.find("        0.125\n") != std::string::npos);
  CHECK(xml.find("</VTKFile>") != std::string::npos);

  std::vector<float> expected_points(xyz.begin(), xyz.end());
  CHECK(array_payload<float>(xml, "Points") == expected_points);
  CHECK(array_payload<float>(xml, "density") == fields[0].values);
  CHECK(array_payload<float>(xml, "velocity") == fields[1].values);
  CHECK(array_payload<float>(xml, "stress") == fields[2].values);
  CHECK(array_payload<std::int64_t>(xml, "connectivity") == std::vector<std::int64_t>{0, 1, 2, 3, 4});
  CHECK(array_payload<std::int64_t>(xml, "offsets") == std::vector<std::int64_t>{1, 2, 3, 4, 5});
  CHECK(array_payload<std::uint8_t>(xml, "types") == std::vector<std::uint8_t>(5, 1));
  CHECK(entries_in(dir.path) == 1);  // no temporary left behind
}

TEST_CASE("vtu_writer: arrays larger than the encoder's buffer and chunks stay intact", "[core][vtu]") {
  terracal::test::ScratchDir dir("vtu_large");
  const fs::path file = dir.path / "big.vtu";
  const std::size_t n = 20011;  // not a multiple of the chunk size, nor of 3 bytes per base64 group
  std::vector<double> xyz(3 * n);
  for (std::size_t i = 0; i < xyz.size(); ++i) xyz[i] = 0.001 * static_cast<double>(i);
  VtuPointData h{"h", 1, std::vector<float>(n)};
  for (std::size_t i = 0; i < n; ++i) h.values[i] = static_cast<float>(i) * 1.5f;
  terracal::write_vtu_points(file, xyz, {h});
  const std::string xml = slurp(file);
  CHECK(array_payload<float>(xml, "Points") == std::vector<float>(xyz.begin(), xyz.end()));
  CHECK(array_payload<float>(xml, "h") == h.values);
  const auto offsets = array_payload<std::int64_t>(xml, "offsets");
  REQUIRE(offsets.size() == n);
  CHECK(offsets.front() == 1);
  CHECK(offsets.back() == static_cast<std::int64_t>(n));
}

TEST_CASE("vtu_writer: zero points gives a valid empty grid", "[core][vtu]") {
  terracal::test::ScratchDir dir("vtu_empty");
  const fs::path file = dir.path / "empty.vtu";
  terracal::write_vtu_points(file, {}, {{"density", 1, {}}, {"velocity", 3, {}}});
  const std::string xml = slurp(file);
  CHECK(xml.find("NumberOfPoints=\"0\" NumberOfCells=\"0\"") != std::string::npos);
  CHECK(array_payload<float>(xml, "Points").empty());
  CHECK(array_payload<float>(xml, "velocity").empty());
  CHECK(array_payload<std::uint8_t>(xml, "types").empty());
  CHECK(entries_in(dir.path) == 1);
}

TEST_CASE("vtu_writer: bad inputs throw InputError naming the field and write nothing", "[core][vtu]") {
  terracal::test::ScratchDir dir("vtu_bad");
  const fs::path file = dir.path / "bad.vtu";
  const std::vector<double> xyz = {0, 0, 0, 1, 1, 1};
  auto message_of = [&](const std::vector<double>& pts, const std::vector<VtuPointData>& fields) -> std::string {
    try {
      terracal::write_vtu_points(file, pts, fields);
    } catch (const terracal::InputError& e) {
      return e.what();
    }
    return "(no InputError)";
  };
  CHECK_THAT(message_of({0, 0, 0, 1}, {}), Catch::Contains("multiple of 3"));
  CHECK_THAT(message_of(xyz, {{"rho", 1, {1.f}}}), Catch::Contains("'rho'") && Catch::Contains("expected 2 points"));
  CHECK_THAT(message_of(xyz, {{"v", 3, {1, 2, 3, 4, 5}}}), Catch::Contains("'v'"));
  CHECK_THAT(message_of(xyz, {{"uv", 2, {1, 2, 3, 4}}}), Catch::Contains("'uv'") && Catch::Contains("components"));
  CHECK_THAT(message_of(xyz, {{"", 1, {1, 2}}}), Catch::Contains("empty name"));
  CHECK_THAT(message_of(xyz, {{"rho", 1, {1, 2}}, {"rho", 1, {3, 4}}}),
             Catch::Contains("'rho'") && Catch::Contains("more than once"));
  CHECK_THROWS_AS(terracal::write_vtu_points(file, xyz, {}, std::nan("")), terracal::InputError);
  CHECK(entries_in(dir.path) == 0);
  // A missing folder is a failed run, not bad input.
  CHECK_THROWS_AS(terracal::write_vtu_points(dir.path / "nope" / "x.vtu", xyz, {}), terracal::RunError);
}

TEST_CASE("vtu_writer: the PVD collection lists the entries in order", "[core][vtu]") {
  terracal::test::ScratchDir dir("vtu_pvd");
  const fs::path file = dir.path / "run.pvd";
  terracal::write_pvd(file, {{0.0, "frames/f_0000.vtu"}, {0.5, "frames/f_0001.vtu"}, {1.25, "frames/a&b.vtu"}});
  const std::string xml = slurp(file);
  CHECK(xml.find("type=\"Collection\"") != std::string::npos);
  const auto a = xml.find("<DataSet timestep=\"0\" group=\"\" part=\"0\" file=\"frames/f_0000.vtu\"/>");
  const auto b = xml.find("<DataSet timestep=\"0.5\" group=\"\" part=\"0\" file=\"frames/f_0001.vtu\"/>");
  const auto c = xml.find("<DataSet timestep=\"1.25\" group=\"\" part=\"0\" file=\"frames/a&amp;b.vtu\"/>");
  REQUIRE(a != std::string::npos);
  REQUIRE(b != std::string::npos);
  REQUIRE(c != std::string::npos);
  CHECK(a < b);
  CHECK(b < c);
  CHECK(entries_in(dir.path) == 1);
  CHECK_THROWS_AS(terracal::write_pvd(file, {{0.0, ""}}), terracal::InputError);
}

TEST_CASE("vtu_writer: a mesh of cells round-trips with its point and cell data", "[core][vtu]") {
  terracal::test::ScratchDir dir("vtu_cells");
  const fs::path file = dir.path / "mesh.vtu";
  // A unit square (quad), a line off its corner and a triangle: 6 points, 3 cells.
  const std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 2, 2, 3, 0, 0};
  terracal::VtuCells cells;
  cells.add(terracal::VtuCellType::quad, {0, 1, 2, 3});
  cells.add(terracal::VtuCellType::line, {2, 4});
  cells.add(terracal::VtuCellType::triangle, {1, 5, 2});
  const std::vector<VtuPointData> point_fields = {{"speed", 1, {0, 1, 2, 3, 4, 5}}};
  const std::vector<VtuPointData> cell_fields = {{"body", 1, {7, -1, 3}}, {"dir", 3, {1, 0, 0, 0, 1, 0, 0, 0, 1}}};
  terracal::write_vtu_cells(file, xyz, cells, point_fields, cell_fields, 2.5);
  const std::string xml = slurp(file);
  CHECK(xml.find("NumberOfPoints=\"6\" NumberOfCells=\"3\"") != std::string::npos);
  // VTK's order inside a Piece: PointData, CellData, Points, Cells.
  const auto pd = xml.find("<PointData>"), cd = xml.find("<CellData>"), pts = xml.find("<Points>"),
             cl = xml.find("<Cells>");
  REQUIRE(cd != std::string::npos);
  CHECK(pd < cd);
  CHECK(cd < pts);
  CHECK(pts < cl);
  CHECK(xml.find("        2.5\n") != std::string::npos);
  CHECK(array_payload<float>(xml, "Points") == std::vector<float>(xyz.begin(), xyz.end()));
  CHECK(array_payload<float>(xml, "speed") == point_fields[0].values);
  CHECK(array_payload<float>(xml, "body") == cell_fields[0].values);
  CHECK(array_payload<float>(xml, "dir") == cell_fields[1].values);
  CHECK(array_payload<std::int64_t>(xml, "connectivity") == std::vector<std::int64_t>{0, 1, 2, 3, 2, 4, 1, 5, 2});
  CHECK(array_payload<std::int64_t>(xml, "offsets") == std::vector<std::int64_t>{4, 6, 9});
  CHECK(array_payload<std::uint8_t>(xml, "types") == std::vector<std::uint8_t>{9, 3, 5});
  CHECK(entries_in(dir.path) == 1);
  // A point cloud keeps its files as before: no CellData section.
  terracal::write_vtu_points(dir.path / "cloud.vtu", xyz, {});
  CHECK(slurp(dir.path / "cloud.vtu").find("CellData") == std::string::npos);
}

TEST_CASE("vtu_writer: bad cells throw InputError naming the cell and write nothing", "[core][vtu]") {
  terracal::test::ScratchDir dir("vtu_bad_cells");
  const fs::path file = dir.path / "bad.vtu";
  const std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 1, 1, 0};
  auto message_of = [&](const terracal::VtuCells& cells, const std::vector<VtuPointData>& cell_fields) {
    try {
      terracal::write_vtu_cells(file, xyz, cells, {}, cell_fields);
    } catch (const terracal::InputError& e) {
      return std::string(e.what());
    }
    return std::string("(no InputError)");
  };
  using terracal::VtuCellType;
  terracal::VtuCells line;
  line.add(VtuCellType::line, {0, 1});
  terracal::VtuCells far = line;
  far.add(VtuCellType::line, {1, 3});
  CHECK_THAT(message_of(far, {}), Catch::Contains("cell 1") && Catch::Contains("point 3 of 3"));
  terracal::VtuCells short_quad;
  short_quad.add(VtuCellType::quad, {0, 1, 2});
  CHECK_THAT(message_of(short_quad, {}), Catch::Contains("cell 0") && Catch::Contains("has 3 points; expected 4"));
  terracal::VtuCells two_gon;
  two_gon.add(VtuCellType::polygon, {0, 1});
  CHECK_THAT(message_of(two_gon, {}), Catch::Contains("expected at least 3"));
  terracal::VtuCells no_type = line;
  no_type.types.clear();
  CHECK_THAT(message_of(no_type, {}), Catch::Contains("1 cell offsets for 0 cell types"));
  terracal::VtuCells trailing = line;
  trailing.connectivity.push_back(2);
  CHECK_THAT(message_of(trailing, {}), Catch::Contains("after the last cell"));
  CHECK_THAT(message_of(line, {{"body", 1, {1, 2}}}),
             Catch::Contains("cell field 'body'") && Catch::Contains("expected 1 cells"));
  CHECK(entries_in(dir.path) == 0);
}
