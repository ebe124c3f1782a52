// `terracal bevameter`: virtual plate-sinkage and annulus-shear tests on CRM or SCM; writes the
// curve files that `terracal calibrate` reads (docs/formats.md, "plate.csv" and "shear.csv").
#include <filesystem>
#include <memory>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "apps/bevameter_options.hpp"
#include "apps/cli_checks.hpp"
#include "apps/commands.hpp"
#include "apps/out_dir.hpp"
#include "apps/report_plots.hpp"
#include "apps/soil_choice.hpp"
#include "core/atomic_file.hpp"
#include "core/errors.hpp"

namespace terracal::app {

namespace {
enum class BevameterTest { kPlate, kShear, kAll };

struct BevameterArgs {
  SoilModel solver = SoilModel::kCrm;
  BevameterTest test = BevameterTest::kAll;
  std::string out;
  BevameterPlan plan;  // the plates and the annulus (apps/bevameter_options.hpp)
  BevameterLists lists;
  bool plots = true;
  TerrainOptions terrain;
};
}  // namespace

Command add_bevameter(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "bevameter", "Virtual bevameter (plate sinkage, annulus shear) on CRM or SCM; writes plate.csv and shear.csv");
  auto a = std::make_shared<BevameterArgs>();
  const std::map<std::string, SoilModel> solvers{{"crm", SoilModel::kCrm}, {"scm", SoilModel::kScm}};
  add_choice(sub, "--solver", a->solver, solvers, "soil model: crm or scm")->required()->default_str("");
  const std::map<std::string, BevameterTest> tests{
      {"plate", BevameterTest::kPlate}, {"shear", BevameterTest::kShear}, {"all", BevameterTest::kAll}};
  add_choice(sub, "--test", a->test, tests, "which test: plate, shear or all");
  sub->add_option("--out", a->out, "output folder")->required();
  add_bevameter_options(sub, a->plan, a->lists);
  sub->add_flag("!--no-plots", a->plots, "skip the PNG plot");
  add_terrain_options(sub, a->terrain, true, true);
  return [a] {
    const OutDir out = prepare_out_dir("--out", a->out);
    const bool plate = a->test != BevameterTest::kShear, shear = a->test != BevameterTest::kPlate;
    BevameterPlan plan = a->plan;
    apply_bevameter_lists(a->lists, plan);
    if (shear && plan.shear_loads.empty())
      throw InputError("--shear-loads: required for the shear test (normal loads in N, e.g. 245,490,736)");
    const SoilChoice soil = choose_soil(a->solver, a->terrain);
    check_bevameter(soil, a->terrain, plan, plate, shear);
    std::filesystem::create_directories(a->out);
    const BevameterCurves c = run_bevameter(soil, a->terrain, plan, plate, shear);
    if (plate) rigs::write_plate_csv(a->out + "/plate.csv", c.plate);
    if (shear) rigs::write_shear_csv(a->out + "/shear.csv", c.shear);
    nlohmann::json run = {{"solver", soil_model_name(a->solver)},
                          {"terrain", c.site},
                          {"plate_wall_seconds", c.plate_wall},
                          {"shear_wall_seconds", c.shear_wall},
                          {"wall_seconds", c.wall}};
    write_text_atomically(a->out + "/run.json", run.dump(2) + "\n");
    if (a->plots) plot_bevameter(a->out, c, nullptr);
    fmt::print("bevameter ({}): {} plate rows in {:.3g} s, {} shear rows in {:.3g} s; written to {}\n",
               soil_model_name(a->solver), c.plate.size(), c.plate_wall, c.shear.size(), c.shear_wall, a->out);
    return 0;
  };
}

}  // namespace terracal::app
