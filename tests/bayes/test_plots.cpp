#include <catch2/catch.hpp>

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../scratch_dir.hpp"
#include "bayes/plots.hpp"
#include "core/errors.hpp"
#include "core/gnuplot.hpp"
#include "core/rng.hpp"
#include "tests/skip.hpp"

namespace fs = std::filesystem;
using terracal::bayes::FitSeries;
using terracal::test::ScratchDir;

namespace {

bool has_png_signature(const fs::path& p) {
  static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::ifstream in(p, std::ios::binary);
  unsigned char head[8] = {};
  in.read(reinterpret_cast<char*>(head), 8);
  return in.gcount() == 8 && std::equal(head, head + 8, sig);
}

std::size_t entries_in(const fs::path& dir) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
  return n;
}

// Bekker-like pressure-sinkage curves p = k z^n for two plates, with noise and a band.
std::vector<FitSeries> two_plates() {
  terracal::Rng rng(5);
  std::vector<FitSeries> out;
  for (int plate = 0; plate < 2; ++plate) {
    FitSeries s;
    s.label = plate == 0 ? "plate b = 0.10 m" : "plate b = 0.20 m";
    const double k = plate == 0 ? 900.0 : 650.0;
    for (int i = 0; i < 15; ++i) {
      const double z = 0.004 * (i + 1);
      const double p = k * std::pow(z * 100.0, 1.1);
      s.x.push_back(z);
      s.fit.push_back(p);
      s.observed.push_back(p * (1.0 + 0.05 * rng.normal()));
      s.lo.push_back(p * 0.9);
      s.hi.push_back(p * 1.1);
    }
    out.push_back(s);
  }
  out[1].lo.clear();  // a series without a band is allowed
  out[1].hi.clear();
  return out;
}

}  // namespace

TEST_CASE("plots: plot_fit writes a PNG with points, lines and bands", "[plots]") {
  if (!terracal::test::gnuplot_or_skip("plots: plot_fit writes a PNG with points, lines and bands")) return;
  ScratchDir dir("fit");
  const fs::path png = dir.path / "fit_pressure_sinkage.png";
  terracal::bayes::plot_fit(png.string(), "Pressure-sinkage fit (posterior mean, 95 % band)", "sinkage z [m]",
                            "pressure p [kPa]", two_plates());
  REQUIRE(fs::exists(png));
  CHECK(fs::file_size(png) > 1000);
  CHECK(has_png_signature(png));
  CHECK(entries_in(dir.path) == 1);  // no temporary image left next to it
}

TEST_CASE("plots: plot_pairs writes a PNG of pairwise marginals", "[plots]") {
  if (!terracal::test::gnuplot_or_skip("plots: plot_pairs writes a PNG of pairwise marginals")) return;
  ScratchDir dir("pairs");
  const fs::path png = dir.path / "pairs.png";
  terracal::Rng rng(11);
  std::vector<std::vector<double>> draws;
  for (int k = 0; k < 5000; ++k) {  // more than the scatter limit: exercises thinning
    const double a = rng.normal(), b = rng.normal();
    draws.push_back(
        {2.0 + 0.3 * a, 0.8 + 0.05 * (0.7 * a + 0.7 * b), 30.0 + 2.0 * b, 1.1e3 * (1 + 0.1 * rng.normal())});
  }
  terracal::bayes::plot_pairs(png.string(), {"n [-]", "k_c [kN/m^(n+1)]", "phi [deg]", "c [Pa]"}, draws);
  REQUIRE(fs::exists(png));
  CHECK(fs::file_size(png) > 1000);
  CHECK(has_png_signature(png));
  CHECK(entries_in(dir.path) == 1);
}

TEST_CASE("plots: bad input and a missing folder throw RunError and leave no file", "[plots]") {
  ScratchDir dir("bad_input");
  std::vector<FitSeries> series = two_plates();
  series[0].fit.pop_back();
  CHECK_THROWS_AS(terracal::bayes::plot_fit((dir.path / "a.png").string(), "t", "x", "y", series), terracal::RunError);
  CHECK_THROWS_AS(terracal::bayes::plot_fit((dir.path / "no_folder" / "b.png").string(), "t", "x", "y", two_plates()),
                  terracal::RunError);
  CHECK_THROWS_AS(terracal::bayes::plot_pairs((dir.path / "c.png").string(), {"a", "b"}, {{1.0, 2.0}, {3.0}}),
                  terracal::RunError);
  CHECK(entries_in(dir.path) == 0);
}

TEST_CASE("plots: a gnuplot error is reported with gnuplot's message", "[plots]") {
  if (!terracal::test::gnuplot_or_skip("plots: a gnuplot error is reported with gnuplot's message")) return;
  ScratchDir dir("gnuplot_error");
  try {
    terracal::run_gnuplot("plot 'no_such_file.dat' using 1:2\n", dir.path.string());
    FAIL("no exception");
  } catch (const terracal::RunError& e) {
    CHECK_THAT(std::string(e.what()), Catch::Contains("no_such_file.dat"));
  }
}
