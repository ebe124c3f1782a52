// `terracal bevameter`: virtual plate-sinkage and annulus-shear tests on CRM or SCM; writes the
// curve files that `terracal calibrate` reads (DESIGN.md section 3).
#include <filesystem>
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <spdlog/spdlog.h>

#include "apps/commands.hpp"
#include "apps/plate_options.hpp"
#include "apps/report_plots.hpp"
#include "apps/soil_choice.hpp"
#include "core/atomic_file.hpp"
#include "core/errors.hpp"

namespace terracal::app {

namespace {
struct BevameterArgs {
  std::string solver, test = "all", out, plates = "0.2,0.3", loads, annulus = "0.15,0.20";
  double max_sinkage = 0.2, shear_angle = 1.0, shear_rate = 1.0, shear_settle = 1.0, shear_step = 0, shear_load_ramp = 0.5;
  BevameterPlan plate;  // speed and CRM bin (apps/plate_options.hpp)
  bool plots = true;
  TerrainOptions terrain;
};
}  // namespace

Command add_bevameter(CLI::App& app) {
  auto* sub = app.add_subcommand("bevameter", "Virtual bevameter (plate sinkage, annulus shear) on CRM or SCM; writes plate.csv and shear.csv");
  auto a = std::make_shared<BevameterArgs>();
  sub->add_option("--solver", a->solver, "crm or scm")->required();
  sub->add_option("--test", a->test, "plate, shear or all")->capture_default_str();
  sub->add_option("--out", a->out, "output folder")->required();
  sub->add_option("--plates", a->plates, "plate radii [m], comma-separated")->capture_default_str();
  sub->add_option("--max-sinkage", a->max_sinkage, "plate sinkage at the end of the stroke [m]")->capture_default_str();
  add_plate_options(sub, a->plate);
  sub->add_option("--shear-loads", a->loads, "annulus normal loads [N], comma-separated (required for shear)");
  sub->add_option("--annulus", a->annulus, "annulus inner,outer radius [m]")->capture_default_str();
  sub->add_option("--shear-angle", a->shear_angle, "angle turned [rad]")->capture_default_str();
  sub->add_option("--shear-rate", a->shear_rate, "annulus angular velocity [rad/s]")->capture_default_str();
  sub->add_option("--shear-settle", a->shear_settle, "settling under the load before turning [s]")->capture_default_str();
  sub->add_option("--shear-load-ramp", a->shear_load_ramp,
                  "the annulus's load grows from zero over this fraction of --shear-settle, as a bevameter's ram puts it on "
                  "(0: dropped at once, which leaves the ring moving, differently in each bin, when it starts to turn; "
                  "results/plate_bin_check, twelfth study); 0 ... 1")
      ->capture_default_str();
  sub->add_option("--shear-step", a->shear_step, "CRM time step of the annulus runs [s] (0: as --step)")->capture_default_str();
  sub->add_flag("!--no-plots", a->plots, "skip the PNG plot");
  add_terrain_options(sub, a->terrain, true, true);
  return [a] {
    if (a->test != "plate" && a->test != "shear" && a->test != "all")
      throw InputError(fmt::format("--test {}: expected plate, shear or all", a->test));
    if (a->solver != "crm" && a->solver != "scm") throw InputError(fmt::format("--solver {}: expected crm or scm", a->solver));
    const bool plate = a->test != "shear", shear = a->test != "plate";
    BevameterPlan plan = a->plate;
    plan.plates = parse_list(a->plates, "--plates");
    plan.max_sinkage = a->max_sinkage;
    const auto ann = parse_list(a->annulus, "--annulus");
    if (ann.size() != 2) throw InputError(fmt::format("--annulus '{}': expected two radii INNER,OUTER", a->annulus));
    plan.inner_radius = ann[0];
    plan.outer_radius = ann[1];
    if (shear) {
      if (a->loads.empty()) throw InputError("--shear-loads: required for the shear test (normal loads in N, e.g. 245,490,736)");
      plan.shear_loads = parse_list(a->loads, "--shear-loads");
    }
    plan.shear_angle = a->shear_angle;
    plan.shear_rate = a->shear_rate;
    plan.shear_settle = a->shear_settle;
    plan.shear_load_ramp = a->shear_load_ramp;
    plan.shear_step = a->shear_step;
    const SoilChoice soil = choose_soil(a->solver, a->terrain);
    std::filesystem::create_directories(a->out);
    const BevameterCurves c = run_bevameter(soil, a->terrain, plan, plate, shear);
    if (plate) rigs::write_plate_csv(a->out + "/plate.csv", c.plate);
    if (shear) rigs::write_shear_csv(a->out + "/shear.csv", c.shear);
    nlohmann::json run = {{"solver", a->solver}, {"terrain", c.site}, {"plate_wall_seconds", c.plate_wall}, {"shear_wall_seconds", c.shear_wall}};
    write_text_atomically(a->out + "/run.json", run.dump(2) + "\n");
    if (a->plots) plot_bevameter(a->out, c, nullptr);
    fmt::print("bevameter ({}): {} plate rows in {:.3g} s, {} shear rows in {:.3g} s; written to {}\n", a->solver, c.plate.size(),
               c.plate_wall, c.shear.size(), c.shear_wall, a->out);
    return 0;
  };
}

}  // namespace terracal::app
