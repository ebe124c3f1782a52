#include "apps/rom_pipeline.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "apps/rom_calibration.hpp"
#include "apps/rom_pipeline_report.hpp"
#include "apps/rom_validation.hpp"
#include "apps/vehicle_outputs.hpp"
#include "core/atomic_file.hpp"
#include "core/errors.hpp"
#include "rom/rom_reference.hpp"
#include "rom/rom_vehicle_json.hpp"

namespace terracal::app {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

struct PipelineManeuver {
  const char* name;
  const char* json;
};
// Training: what a calibration needs to see (drive, both turn directions, a transient at speed).
constexpr PipelineManeuver kTraining[] = {
    {"accel", R"({"type": "straight_acceleration", "throttle": 0.5, "start_time": 0.5, "initial_speed": 5, "end_time": 6})"},
    {"step_left", R"({"type": "step_steer", "steering": 0.2, "step_time": 1, "initial_speed": 10, "end_time": 5})"},
    {"step_right", R"({"type": "step_steer", "steering": -0.2, "step_time": 1, "initial_speed": 10, "end_time": 5})"},
    {"dlc", R"({"type": "iso3888_1", "initial_speed": 15, "target_speed": 15})"}};
// Validation: manoeuvres the calibration did not see.
constexpr PipelineManeuver kValidation[] = {
    {"sine", R"({"type": "single_sine", "amplitude": 0.2, "frequency": 0.5, "start_time": 1, "initial_speed": 12, "end_time": 6})"},
    {"turn", R"({"type": "constant_steer", "steering": 0.15, "target_speed": 8, "initial_speed": 8, "end_time": 8})"}};

// The full vehicle on one manoeuvre (its JSON written to maneuvers/), its outputs in full/<name>.
std::string run_full(const RomPipelineSettings& s, const vehicle::FullVehicleSpec& spec, const PipelineManeuver& m,
                     std::vector<AccuracyCostRow>& rows) {
  const std::string json_path = s.out + "/maneuvers/" + m.name + ".json";
  write_text_atomically(json_path, std::string(m.json) + "\n");
  Maneuver maneuver = Maneuver::read(json_path, maneuver_vehicle(spec));
  vehicle::VehicleRunOptions o;
  o.end_time = maneuver.end_time();
  o.initial_speed = maneuver.initial_speed();
  const std::string dir = s.out + "/full/" + m.name;
  std::filesystem::create_directories(dir);
  const vehicle::VehicleRunResult r = vehicle::run_full_vehicle(spec, nullptr, &maneuver, o);
  write_vehicle_outputs(dir, {s.vehicle, "rigid", "", json_path, false, false}, o, r);
  spdlog::info("pipeline-rom: full vehicle on {}: {:.3g} s simulated in {:.3g} s wall", m.name, o.end_time,
               r.wall_seconds);
  rows.push_back({m.name, "full vehicle", "cpu (1 core)", 0, 0, r.wall_seconds / o.end_time});
  return dir;
}

double rmse(const rom::RomReference& ref, const std::vector<rom::RomSample>& run, double rom::RomSample::*field,
            rom::RomChannel ch) {
  double sum = 0;
  std::size_t k = 0;
  for (std::size_t i = 0; i < ref.time.size(); ++i) {
    while (k + 1 < run.size() && run[k + 1].time <= ref.time[i]) ++k;
    double v = run[k].*field;
    if (k + 1 < run.size()) {
      const double w = (ref.time[i] - run[k].time) / (run[k + 1].time - run[k].time);
      v += w * (run[k + 1].*field - v);
    }
    const double d = v - ref.values[ch][i];
    sum += d * d;
  }
  return std::sqrt(sum / double(ref.time.size()));
}

// Each ROM level's preset and the calibrated model on a validation reference: errors and cost.
void compare_roms(const RomPipelineSettings& s, const std::string& ref_dir, const std::string& name,
                  std::vector<AccuracyCostRow>& rows) {
  const rom::RomReference ref = rom::read_rom_reference(ref_dir);
  const std::string preset = s.rom_vehicle.empty() ? s.vehicle : s.rom_vehicle;
  struct Candidate {
    std::string label;
    rom::RomVehicle vehicle;
    rom::RomModel model;
  };
  std::vector<Candidate> candidates;
  for (rom::RomModel m : {rom::RomModel::k11Dof, rom::RomModel::k18Dof, rom::RomModel::k24Dof})
    candidates.push_back({fmt::format("{} preset", rom::model_name(m)), rom::load_rom_vehicle(preset), m});
  candidates.push_back({fmt::format("{} calibrated", rom::model_name(s.model)),
                        rom::load_rom_vehicle(s.out + "/calibration/rom_params.json"), s.model});
  for (const Candidate& c : candidates) {
    rom::RomRunOptions o;
    o.model = c.model;
    o.end_time = ref.end_time();
    o.initial_speed = ref.initial_speed;
    rom::RomDriver d;
    d.series = &ref.driver;
    rom::RomRunResult best;
    double wall = 1e30;
    for (int rep = 0; rep < 3; ++rep) {  // the fastest of three: these runs take milliseconds
      rom::RomRunResult r = rom::run_rom(c.vehicle, d, o);
      if (r.wall_seconds < wall) wall = r.wall_seconds, best = std::move(r);
    }
    rows.push_back({name, c.label, "cpu (1 core)", rmse(ref, best.samples, &rom::RomSample::vx, rom::kRcVx),
                    rmse(ref, best.samples, &rom::RomSample::yaw_rate, rom::kRcYawRate), wall / o.end_time});
  }
}

}  // namespace

RomPipelineOutcome run_rom_pipeline(const RomPipelineSettings& s) {
  const auto t0 = Clock::now();
  RomPipelineOutcome out;
  const vehicle::FullVehicleSpec spec = vehicle::load_full_vehicle(s.vehicle);
  const std::string preset = s.rom_vehicle.empty() ? s.vehicle : s.rom_vehicle;
  rom::load_rom_vehicle(preset);  // refused now, not after the full-vehicle runs
  std::filesystem::create_directories(s.out + "/maneuvers");
  std::vector<std::string> training, validation;
  std::vector<AccuracyCostRow> full_rows;
  for (const auto& m : kTraining) training.push_back(run_full(s, spec, m, full_rows));
  for (const auto& m : kValidation) validation.push_back(run_full(s, spec, m, full_rows));
  out.full_seconds = since(t0);

  const auto t1 = Clock::now();
  RomCalibrationSettings cal;
  cal.model = s.model;
  cal.vehicle = preset;
  cal.references = training;
  cal.out = s.out + "/calibration";
  cal.seed = s.seed;
  cal.max_draws = s.max_draws;
  cal.device = s.device;
  cal.plots = s.plots;
  std::filesystem::create_directories(cal.out);
  const RomCalibrationOutcome calibration = run_rom_calibration(cal);
  out.converged = calibration.result.converged;
  out.calibration_seconds = since(t1);

  const auto t2 = Clock::now();
  RomValidationSettings val;
  val.posterior = cal.out;
  val.references = validation;
  val.draws = s.draws;
  val.device = s.device;
  val.out = s.out + "/validation";
  val.plots = s.plots;
  const RomValidationOutcome validated = run_rom_validation(val);
  out.validation_seconds = since(t2);

  const auto t3 = Clock::now();
  for (std::size_t i = 0; i < validation.size(); ++i) {
    for (const auto& r : full_rows)
      if (r.maneuver == kValidation[i].name) out.accuracy_cost.push_back(r);
    compare_roms(s, validation[i], kValidation[i].name, out.accuracy_cost);
    // The posterior-predictive batch: the cost per vehicle of a calibrated ROM run as a batch.
    const auto& vr = validated.references[i];
    const double simulated = rom::read_rom_reference(validation[i]).end_time();
    out.accuracy_cost.push_back({kValidation[i].name, fmt::format("{} calibrated (batch of {})", rom::model_name(s.model),
                                                                  validated.draws),
                                 validated.device, NAN, NAN,
                                 vr.wall_seconds / (double(validated.draws) * simulated)});
  }
  out.comparison_seconds = since(t3);
  out.total_seconds = since(t0);
  write_rom_pipeline_report(s, out, calibration, validated);
  return out;
}

}  // namespace terracal::app
