// `terracal synthesize`: bevameter curves from known SCM parameters, through the same forward
// models the calibrator fits. Makes the demo data set (studies/demo/make_demo_data.sh) and test data.
#include <filesystem>
#include <memory>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "apps/cli_checks.hpp"
#include "apps/commands.hpp"
#include "apps/out_dir.hpp"
#include "bayes/synthetic_data.hpp"
#include "core/errors.hpp"
#include "lowfi/scm_soil.hpp"

namespace terracal::app {

namespace {
struct SynthesizeArgs {
  std::string truth, out;
  std::uint64_t seed = 1;
  bayes::SyntheticDesign design;
  std::vector<double> annulus{0.15, 0.20};
};

// The parameters the forward models take, from a set checked as `wheel` and `bevameter` check it.
bayes::ParamVector truth_parameters(const std::string& path) {
  const lowfi::ScmSoil s = lowfi::read_scm_json(path);
  bayes::ParamVector p{};
  p[bayes::kKc] = s.Kc;
  p[bayes::kKphi] = s.Kphi;
  p[bayes::kN] = s.n;
  p[bayes::kCohesion] = s.cohesion;
  p[bayes::kFriction] = s.friction_deg;
  p[bayes::kJanosi] = s.janosi_k;
  return p;
}

void add_design_options(CLI::App* sub, SynthesizeArgs& a) {
  using R = bayes::SyntheticRanges;
  auto& d = a.design;
  sub->add_option("--plates", d.plate_radii, "plate radii [m]")
      ->delimiter(',')
      ->check(in_range(R::kPlateRadius))
      ->capture_default_str();
  sub->add_option("--max-sinkage", d.max_sinkage, "deepest sinkage [m]")
      ->check(in_range(R::kMaxSinkage))
      ->capture_default_str();
  sub->add_option("--plate-points", d.plate_points, "samples per plate")
      ->transform(whole_in(1, R::kMaxPoints))
      ->capture_default_str();
  sub->add_option("--annulus", a.annulus, "annulus inner,outer radius [m]")
      ->delimiter(',')
      ->expected(2)
      ->check(in_range(R::kAnnulusRadius))
      ->capture_default_str();
  sub->add_option("--pressures", d.shear_pressures, "normal pressures of the shear tests [Pa]")
      ->delimiter(',')
      ->check(in_range(R::kPressure))
      ->capture_default_str();
  sub->add_option("--max-angle", d.max_angle, "largest shear angle [rad]")
      ->check(in_range(R::kMaxAngle))
      ->capture_default_str();
  sub->add_option("--shear-points", d.shear_points, "samples per shear test")
      ->transform(whole_in(1, R::kMaxPoints))
      ->capture_default_str();
  sub->add_option("--noise", d.relative_noise,
                  "relative noise sd (0.02 = 2 %); above 0.2 some values would turn negative (docs/formats.md)")
      ->check(in_range(R::kRelativeNoise))
      ->capture_default_str();
}
}  // namespace

Command add_synthesize(CLI::App& app) {
  auto* sub =
      app.add_subcommand("synthesize", "Write synthetic plate and shear curves (CSV) from known SCM parameters");
  auto a = std::make_shared<SynthesizeArgs>();
  sub->add_option("--truth", a->truth, "SCM parameter file (Chrono JSON with 'Soil parameters')")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--out", a->out, "output folder: plate.csv, shear.csv")->required();
  add_seed_option(sub, a->seed, "noise seed");
  add_design_options(sub, *a);
  return [a] {
    const OutDir out = prepare_out_dir("--out", a->out);
    auto& d = a->design;
    d.annulus_inner = a->annulus[0];
    d.annulus_outer = a->annulus[1];
    bayes::validate(d);
    const bayes::ParamVector truth = truth_parameters(a->truth);
    std::filesystem::create_directories(a->out);
    Rng rng(a->seed);
    bayes::write_plate_csv(a->out + "/plate.csv", bayes::synthesize_plate(truth, d, rng));
    bayes::write_shear_csv(a->out + "/shear.csv", bayes::synthesize_shear(truth, d, rng));
    spdlog::info("wrote {}/plate.csv and {}/shear.csv", a->out, a->out);
    return 0;
  };
}

}  // namespace terracal::app
