// Plate phases and plate sizes as the calibrator sees them (DESIGN.md section 3): the Bekker law is
// fitted to loading beyond the previous maximum sinkage, and only plates with such rows count.
#include <catch2/catch.hpp>

#include <fstream>

#include "bayes/observations.hpp"
#include "../scratch_dir.hpp"

using namespace terracal;
using namespace terracal::bayes;

TEST_CASE("load / unload / reload: only loading beyond the previous maximum is fitted", "[bayes][observations]") {
  const test::ScratchDir dir("phases");
  const std::string path = dir.str() + "/plate.csv";
  std::ofstream(path) << "plate_radius_m,sinkage_m,force_N,phase\n"
                         "0.1,0.01,300,load\n0.1,0.02,650,load\n0.1,0.03,1000,load\n"
                         "0.1,0.025,400,unload\n0.1,0.02,100,unload\n"
                         "0.1,0.022,200,load\n0.1,0.026,500,reload\n0.1,0.035,1200,reload\n"
                         "0.2,0.01,1100,\n0.2,0.02,2300,\n"
                         "0.3,0,0,load\n";  // a plate with no sinkage: no information
  const PlateData d = load_plate_csv(path);
  std::vector<double> fitted;
  for (const auto& p : d.points)
    if (p.fitted) fitted.push_back(p.sinkage);
  CHECK(fitted == std::vector<double>{0.01, 0.02, 0.03, 0.035, 0.01, 0.02});
  CHECK(d.radii == std::vector<double>{0.1, 0.2});
}
