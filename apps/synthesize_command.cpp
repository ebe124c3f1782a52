// `terracal synthesize`: bevameter curves from known SCM parameters, through the same forward
// models the calibrator fits. Makes the demo data set (studies/demo/make_demo_data.sh) and test data.
#include <filesystem>
#include <memory>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "apps/commands.hpp"
#include "bayes/scm_json_read.hpp"
#include "bayes/synthetic_data.hpp"
#include "core/errors.hpp"

namespace terracal::app {

namespace {
struct SynthesizeArgs {
  std::string truth, out;
  std::uint64_t seed = 1;
  bayes::SyntheticDesign design;
  std::vector<double> annulus{0.15, 0.20};
};

void check_positive(const char* key, double v) {
  if (!(v > 0)) throw InputError(fmt::format("{} {}: expected a value > 0", key, v));
}
}  // namespace

Command add_synthesize(CLI::App& app) {
  auto* sub =
      app.add_subcommand("synthesize", "Write synthetic plate and shear curves (CSV) from known SCM parameters");
  auto a = std::make_shared<SynthesizeArgs>();
  auto& d = a->design;
  sub->add_option("--truth", a->truth, "SCM parameter file (Chrono JSON with 'Soil parameters')")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--out", a->out, "output folder: plate.csv, shear.csv")->required();
  sub->add_option("--seed", a->seed, "noise seed")->capture_default_str();
  sub->add_option("--plates", d.plate_radii, "plate radii [m]")->delimiter(',')->capture_default_str();
  sub->add_option("--max-sinkage", d.max_sinkage, "deepest sinkage [m]")->capture_default_str();
  sub->add_option("--plate-points", d.plate_points, "samples per plate")->capture_default_str();
  sub->add_option("--annulus", a->annulus, "annulus inner,outer radius [m]")
      ->delimiter(',')
      ->expected(2)
      ->capture_default_str();
  sub->add_option("--pressures", d.shear_pressures, "normal pressures of the shear tests [Pa]")
      ->delimiter(',')
      ->capture_default_str();
  sub->add_option("--max-angle", d.max_angle, "largest shear angle [rad]")->capture_default_str();
  sub->add_option("--shear-points", d.shear_points, "samples per shear test")->capture_default_str();
  sub->add_option("--noise", d.relative_noise, "relative noise sd (0.02 = 2 %)")->capture_default_str();
  return [a] {
    auto& d = a->design;
    for (double r : d.plate_radii) check_positive("--plates", r);
    for (double p : d.shear_pressures) check_positive("--pressures", p);
    check_positive("--max-sinkage", d.max_sinkage);
    check_positive("--max-angle", d.max_angle);
    if (d.plate_points < 1 || d.shear_points < 1)
      throw InputError("--plate-points/--shear-points: expected at least 1");
    if (!(a->annulus[1] > a->annulus[0] && a->annulus[0] >= 0))
      throw InputError(fmt::format("--annulus {},{}: expected 0 <= inner < outer", a->annulus[0], a->annulus[1]));
    if (d.relative_noise < 0) throw InputError(fmt::format("--noise {}: expected >= 0", d.relative_noise));
    d.annulus_inner = a->annulus[0];
    d.annulus_outer = a->annulus[1];
    const bayes::ParamVector truth = bayes::read_scm_soil_parameters(a->truth);
    std::filesystem::create_directories(a->out);
    Rng rng(a->seed);
    bayes::write_plate_csv(a->out + "/plate.csv", bayes::synthesize_plate(truth, d, rng));
    bayes::write_shear_csv(a->out + "/shear.csv", bayes::synthesize_shear(truth, d, rng));
    spdlog::info("wrote {}/plate.csv and {}/shear.csv", a->out, a->out);
    return 0;
  };
}

}  // namespace terracal::app
