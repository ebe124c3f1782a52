#include <catch2/catch.hpp>

#include <hdf5.h>
#include <hdf5_hl.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "../scratch_dir.hpp"
#include "bayes/posterior_h5.hpp"
#include "core/errors.hpp"

namespace fs = std::filesystem;
using terracal::RunError;
using terracal::bayes::Group;
using terracal::bayes::InferenceData;
using terracal::bayes::Variable;
using terracal::test::ScratchDir;

namespace {

constexpr std::size_t kChains = 2, kDraws = 3, kObs = 4;

// Values that survive only an exact (bitwise) round trip: no two alike, tiny, huge, negative.
std::vector<double> values(std::size_t n, double scale) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = scale * (0.1 + static_cast<double>(i)) / 3.0 * (i % 2 ? -1.0 : 1.0);
  if (n > 2) v[2] = 1e-300;
  return v;
}

InferenceData small_idata() {
  InferenceData id;
  id.groups.push_back(
      Group{"posterior",
            {Variable{"c", {"chain", "draw"}, {kChains, kDraws}, values(kChains * kDraws, 1e3), "Pa"},
             Variable{"phi", {"chain", "draw"}, {kChains, kDraws}, values(kChains * kDraws, 0.5), "rad"}}});
  id.groups.push_back(Group{
      "sample_stats", {Variable{"lp", {"chain", "draw"}, {kChains, kDraws}, values(kChains * kDraws, -7.0), ""}}});
  id.groups.push_back(Group{"observed_data", {Variable{"sinkage", {"plate_obs"}, {kObs}, values(kObs, 0.01), "m"}}});
  id.groups.push_back(Group{"posterior_predictive",
                            {Variable{"sinkage",
                                      {"chain", "draw", "plate_obs"},
                                      {kChains, kDraws, kObs},
                                      values(kChains * kDraws * kObs, 0.02),
                                      "m"}}});
  return id;
}

std::vector<char> file_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Dimension name of one axis, straight from the HDF5 dimension-scale API.
std::string attached_scale_name(hid_t file, const std::string& dataset, unsigned axis) {
  const hid_t ds = H5Dopen2(file, dataset.c_str(), H5P_DEFAULT);
  REQUIRE(ds >= 0);
  REQUIRE(H5DSget_num_scales(ds, axis) == 1);
  std::string name;
  auto visitor = [](hid_t, unsigned, hid_t scale, void* out) -> herr_t {
    char buf[256] = {};
    if (H5DSget_scale_name(scale, buf, sizeof buf) <= 0) return -1;
    *static_cast<std::string*>(out) = buf;
    return 1;
  };
  CHECK(H5DSiterate_scales(ds, axis, nullptr, visitor, &name) >= 0);
  H5Dclose(ds);
  return name;
}

std::string text_attribute(hid_t loc, const std::string& object, const std::string& name) {
  const hid_t attr = H5Aopen_by_name(loc, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT);
  REQUIRE(attr >= 0);
  const hid_t type = H5Aget_type(attr);
  std::string buf(H5Tget_size(type), '\0');
  CHECK(H5Aread(attr, type, buf.data()) >= 0);
  H5Tclose(type);
  H5Aclose(attr);
  return buf.substr(0, std::strlen(buf.c_str()));
}

bool folder_is_empty(const fs::path& p) { return fs::is_empty(p); }

}  // namespace

TEST_CASE("posterior_h5: round trip keeps groups, variables, dimension names, units and values exactly",
          "[posterior_h5]") {
  ScratchDir dir("h5_roundtrip");
  const fs::path file = dir.path / "posterior.h5";
  const InferenceData written = small_idata();
  terracal::bayes::write_inference_data_h5(file.string(), written);

  const InferenceData read = terracal::bayes::read_inference_data_h5(file.string());
  REQUIRE(read.groups.size() == written.groups.size());
  for (std::size_t g = 0; g < written.groups.size(); ++g) {
    const Group& a = written.groups[g];
    const Group& b = read.groups[g];
    CHECK(b.name == a.name);  // creation order is kept
    REQUIRE(b.variables.size() == a.variables.size());
    for (std::size_t v = 0; v < a.variables.size(); ++v) {
      INFO(a.name << "/" << a.variables[v].name);
      CHECK(b.variables[v].name == a.variables[v].name);
      CHECK(b.variables[v].dims == a.variables[v].dims);
      CHECK(b.variables[v].shape == a.variables[v].shape);
      CHECK(b.variables[v].units == a.variables[v].units);
      REQUIRE(b.variables[v].data.size() == a.variables[v].data.size());
      CHECK(std::memcmp(b.variables[v].data.data(), a.variables[v].data.data(),
                        a.variables[v].data.size() * sizeof(double)) == 0);
    }
  }
}

TEST_CASE("posterior_h5: dimensions are HDF5 dimension scales holding 0..n-1, attached to every axis",
          "[posterior_h5]") {
  ScratchDir dir("h5_scales");
  const fs::path path = dir.path / "posterior.h5";
  terracal::bayes::write_inference_data_h5(path.string(), small_idata());

  const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(file >= 0);

  CHECK(attached_scale_name(file, "posterior/c", 0) == "chain");
  CHECK(attached_scale_name(file, "posterior/c", 1) == "draw");
  CHECK(attached_scale_name(file, "sample_stats/lp", 1) == "draw");
  CHECK(attached_scale_name(file, "observed_data/sinkage", 0) == "plate_obs");
  CHECK(attached_scale_name(file, "posterior_predictive/sinkage", 0) == "chain");
  CHECK(attached_scale_name(file, "posterior_predictive/sinkage", 1) == "draw");
  CHECK(attached_scale_name(file, "posterior_predictive/sinkage", 2) == "plate_obs");

  // The scale itself: int64 coordinates 0..n-1, as ArviZ writes chain and draw.
  const hid_t obs = H5Dopen2(file, "posterior_predictive/plate_obs", H5P_DEFAULT);
  REQUIRE(obs >= 0);
  CHECK(H5DSis_scale(obs) > 0);
  const hid_t type = H5Dget_type(obs);
  CHECK(H5Tget_class(type) == H5T_INTEGER);
  CHECK(H5Tget_size(type) == 8);
  H5Tclose(type);
  std::vector<std::int64_t> index(kObs, -1);
  CHECK(H5Dread(obs, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, index.data()) >= 0);
  CHECK(index == std::vector<std::int64_t>{0, 1, 2, 3});
  H5Dclose(obs);

  CHECK(text_attribute(file, "posterior/c", "units") == "Pa");
  CHECK(H5Aexists_by_name(file, "sample_stats/lp", "units", H5P_DEFAULT) == 0);  // empty units: no attribute
  CHECK(text_attribute(file, ".", "inference_library") == "terracal");
  CHECK(H5Aexists_by_name(file, ".", "created_at", H5P_DEFAULT) == 0);  // no timestamps: reproducible files
  H5Fclose(file);
}

TEST_CASE("posterior_h5: writing the same object twice gives byte-identical files", "[posterior_h5]") {
  ScratchDir dir("h5_identical");
  const fs::path a = dir.path / "a.h5", b = dir.path / "b.h5";
  terracal::bayes::write_inference_data_h5(a.string(), small_idata());
  terracal::bayes::write_inference_data_h5(b.string(), small_idata());
  const std::vector<char> ba = file_bytes(a), bb = file_bytes(b);
  REQUIRE(!ba.empty());
  CHECK(ba == bb);

  // Overwriting an existing file gives the same bytes again (no leftovers from the old file).
  terracal::bayes::write_inference_data_h5(a.string(), small_idata());
  CHECK(file_bytes(a) == bb);
}

TEST_CASE("posterior_h5: inconsistent objects are rejected before anything is written", "[posterior_h5]") {
  ScratchDir dir("h5_reject");
  const fs::path file = dir.path / "bad.h5";
  InferenceData id = small_idata();

  SECTION("dims and shape of different lengths") { id.groups[0].variables[0].shape = {kChains}; }
  SECTION("data size differs from the shape") { id.groups[0].variables[1].data.pop_back(); }
  SECTION("a dimension with two lengths in one group") {
    id.groups[0].variables[1].shape = {kChains, kDraws + 1};
    id.groups[0].variables[1].data.resize(kChains * (kDraws + 1));
  }
  SECTION("a zero-length dimension") {
    id.groups[2].variables[0].shape = {0};
    id.groups[2].variables[0].data.clear();
  }
  SECTION("a variable named like a dimension") { id.groups[1].variables[0].name = "draw"; }
  SECTION("two groups of the same name") { id.groups[3].name = "posterior"; }

  REQUIRE_THROWS_AS(terracal::bayes::write_inference_data_h5(file.string(), id), RunError);
  CHECK(folder_is_empty(dir.path));
}

TEST_CASE("posterior_h5: the error message names the file and the problem", "[posterior_h5]") {
  InferenceData id = small_idata();
  id.groups[0].variables[1].data.pop_back();
  try {
    terracal::bayes::write_inference_data_h5("/tmp/some_file.h5", id);
    FAIL("no exception");
  } catch (const RunError& e) {
    const std::string msg = e.what();
    CHECK_THAT(msg, Catch::Contains("/tmp/some_file.h5") && Catch::Contains("phi") && Catch::Contains("data has 5"));
  }
}

TEST_CASE("posterior_h5: a failing write leaves no file", "[posterior_h5]") {
  ScratchDir dir("h5_fail");

  SECTION("the folder does not exist") {
    const fs::path missing = dir.path / "no_such_folder" / "posterior.h5";
    try {
      terracal::bayes::write_inference_data_h5(missing.string(), small_idata());
      FAIL("no exception");
    } catch (const RunError& e) {
      CHECK_THAT(std::string(e.what()), Catch::Contains(missing.string()));
    }
    CHECK_FALSE(fs::exists(missing.parent_path()));
    CHECK(folder_is_empty(dir.path));
  }

  SECTION("the final name is taken by a folder: the rename fails and the temporary is removed") {
    const fs::path blocked = dir.path / "posterior.h5";
    fs::create_directory(blocked);
    fs::create_directory(blocked / "keep");  // a non-empty folder cannot be replaced by a rename
    REQUIRE_THROWS_AS(terracal::bayes::write_inference_data_h5(blocked.string(), small_idata()), RunError);
    CHECK(fs::is_directory(blocked / "keep"));
    std::size_t entries = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir.path)) ++entries;
    CHECK(entries == 1);  // only the folder; no .posterior.h5.tmp.* left behind
  }
}

TEST_CASE("posterior_h5: reading a missing or non-HDF5 file throws RunError", "[posterior_h5]") {
  ScratchDir dir("h5_read_bad");
  CHECK_THROWS_AS(terracal::bayes::read_inference_data_h5((dir.path / "none.h5").string()), RunError);
  const fs::path text = dir.path / "text.h5";
  std::ofstream(text) << "not hdf5\n";
  CHECK_THROWS_AS(terracal::bayes::read_inference_data_h5(text.string()), RunError);
}
