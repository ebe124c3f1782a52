// The plate rig's phase labels (docs/formats.md, "plate.csv"): the calibrator rejects an unload row deeper
// than the deepest load row, so the rig must label each row by where the plate actually went. A
// CRM terrain starts a leg of the schedule at a step that may still move the plate with the old
// leg's velocity; with every step recorded, that step must stay a load row.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>

#include "highfi/crm/crm_terrain.hpp"
#include "tests/highfi/crm/crm_test_scenes.hpp"
#include "virtual_bevameter/plate_rig.hpp"

using namespace terracal;

TEST_CASE("Plate rig: phases follow the plate's motion, no unload row lies below the load leg", "[rigs][crm]") {
  const CrmScene sc = test::scene_from(test::bed_scene_json(0.02, 16, 8, 0.02));
  const CrmSite site(sc, test::validation_device(), "");
  rigs::PlateTest t;
  t.radius = 0.06;
  t.max_sinkage = 0.02;
  t.speed = 0.1;
  t.thickness = 0.04;
  t.samples = 1000000;  // every step a row: the turning steps are in the file
  const auto rows = rigs::run_plate(site, t);
  REQUIRE(rows.size() > 50);
  double deepest = -1;
  int unloads = 0, reloads = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    INFO("row " << i << ": " << r.phase << " at " << r.sinkage << " m");
    if (r.phase == "load") {
      CHECK(r.sinkage >= deepest - 1e-12);  // the load leg only goes down
      deepest = std::max(deepest, r.sinkage);
    } else if (r.phase == "unload") {
      ++unloads;
      CHECK(r.sinkage <= deepest);
      CHECK(r.sinkage <= rows[i - 1].sinkage);  // it went up over its step (or stood)
    } else {
      REQUIRE(r.phase == "reload");
      ++reloads;
      CHECK(r.sinkage >= rows[i - 1].sinkage);  // it went down over its step (or stood, after the stroke)
    }
  }
  CHECK(unloads > 3);
  CHECK(reloads > 3);
  CHECK(rows.front().phase == "load");
  CHECK(rows.back().sinkage == Approx(t.max_sinkage).margin(2e-3));
}
