// `terracal demo`: the main job on its embedded default. Until the CRM pipeline exists it
// calibrates the example data set of studies/demo (made by make_demo_data.sh from truth.json,
// embedded in the program at build time) and writes the results to results/demo/.
#include <filesystem>
#include <memory>

#include <spdlog/spdlog.h>

#include "apps/calibration_run.hpp"
#include "apps/commands.hpp"
#include "core/atomic_file.hpp"
#include "demo_data.hpp"  // generated: kDemoPlateCsv, kDemoShearCsv, kDemoTruthJson

namespace terracal::app {

Command add_demo(CLI::App& app) {
  auto* sub = app.add_subcommand("demo", "Calibrate the embedded example data set (studies/demo) and write results/demo/");
  auto out = std::make_shared<std::string>("results/demo");
  auto seed = std::make_shared<std::uint64_t>(2026);
  sub->add_option("--out", *out, "output folder")->capture_default_str();
  sub->add_option("--seed", *seed, "random seed")->capture_default_str();
  return [out, seed] {
    const std::string data = *out + "/data";
    std::filesystem::create_directories(data);
    write_text_atomically(data + "/plate.csv", kDemoPlateCsv);
    write_text_atomically(data + "/shear.csv", kDemoShearCsv);
    write_text_atomically(data + "/truth.json", kDemoTruthJson);
    spdlog::info("demo: the data set of studies/demo (true parameters in {}/truth.json)", data);
    CalibrationRequest req;
    req.plate_csv = data + "/plate.csv";
    req.shear_csv = data + "/shear.csv";
    req.out_dir = *out;
    req.seed = *seed;
    return run_calibration(req);
  };
}

}  // namespace terracal::app
