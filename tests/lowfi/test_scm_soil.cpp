// The SCM soil's keys: one table of ranges serves the file reader and the check of sets built in code.
#include <catch2/catch.hpp>

#include "core/errors.hpp"
#include "lowfi/scm_soil.hpp"

using namespace terracal;
using namespace terracal::lowfi;
using Catch::Matchers::Contains;

TEST_CASE("SCM soil: the reader and validate() refuse the same values", "[lowfi][scm]") {
  const nlohmann::json good = scm_soil_json(reference_dry_sand());
  const ScmSoil read = parse_scm_soil(good, "sand");
  CHECK(read.friction_deg == 28);
  CHECK(read.janosi_k == 0.025);
  CHECK_NOTHROW(validate(read, "sand"));
  for (const auto& k : scm_soil_keys()) {
    INFO(k.name);
    const double bad = k.range.hi * 2 + 1;  // above every range
    nlohmann::json j = good;
    j[k.name] = bad;
    CHECK_THROWS_WITH(parse_scm_soil(j, "f.json"), Contains(std::string("f.json: key 'Soil parameters.") + k.name));
    ScmSoil s = read;
    s.*k.field = bad;
    CHECK_THROWS_WITH(validate(s, "built"), Contains(std::string("built: key 'Soil parameters.") + k.name));
    // A required key left out is refused; the others take Chrono's defaults.
    j = good;
    j.erase(k.name);
    if (k.required)
      CHECK_THROWS_AS(parse_scm_soil(j, "f.json"), InputError);
    else
      CHECK(parse_scm_soil(j, "f.json").*k.field == ScmSoil{}.*k.field);
  }
  nlohmann::json typo = good;
  typo["Bekker Kx"] = 1;
  CHECK_THROWS_WITH(parse_scm_soil(typo, "f.json"), Contains("unknown key 'Soil parameters.Bekker Kx'"));
}
