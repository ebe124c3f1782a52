#pragma once
// `terracal study`'s spec (docs/study.md): the mission's three demands as single-wheel runs of one
// solver, each run a job of a campaign (resumable, MPI-ready):
//   accuracy-cost  each fidelity knob from coarse to fine, the others at their finest; the reference
//                  is every knob at its finest;
//   stability      sweeps of step, gravity, stiffness, slip and more, each alone from the base
//                  settings, plus a wheel at standstill;
//   effects        each effect variant against the base settings.
// A spec holds the scene (wheel, soil, base options) and each study's lists; every key is optional
// and replaces the embedded default's for the solver, so `--spec` names only what it changes.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/campaign_spec.hpp"
#include "apps/rig_runs.hpp"

namespace terracal::app {

enum class StudyKind { kAccuracyCost, kStability, kEffects };
inline const std::vector<std::string> kStudyKinds = {"accuracy-cost", "stability", "effects"};
std::string study_kind_name(StudyKind k);

// One single-wheel run of a study.
struct StudyRun {
  std::string group;  // the knob, the sweep or the effect variant's name; "reference" / "base"
  std::string label;  // folder-safe: "grid_0.005"
  double value = 0;   // the knob's or the sweep's value (0 for effects, the reference and standstill)
  nlohmann::ordered_json options;  // wheel options (base with the run's own over them)
  nlohmann::ordered_json soil;     // the soil this run uses: the base's, or a copy (gravity, stiffness)
  nlohmann::ordered_json wheel;    // the wheel (standstill: angular_velocity 0)
  bool reference = false;          // accuracy-cost: the reference; effects: the base
};

struct StudySpec {
  StudyKind kind = StudyKind::kAccuracyCost;
  SoilModel solver = SoilModel::kScm;
  std::string source;            // the spec file, or "the embedded default"
  nlohmann::ordered_json merged;  // the default with the file's keys over it: what ran (DIR/spec.json)
  std::vector<StudyRun> runs;    // the reference / base first
};

// The embedded default spec of a solver (crm, scm, wong-reece).
nlohmann::ordered_json default_study_spec(SoilModel solver);

// Reads `path` (empty: the default alone) over the solver's default and makes the runs. Throws
// InputError naming the file, the key and the value for an unknown key, a wheel option the wheel
// command does not take or refuses, an empty or unordered list, a soil without the value a sweep
// scales, or a study the solver has nothing for (Wong-Reece has no effects).
StudySpec read_study_spec(StudyKind kind, SoilModel solver, const std::string& path);

// The runs as campaign jobs (stage: the study's name); inline wheels and soils are written into
// DIR/inputs/ before a job starts.
std::vector<CampaignJob> study_jobs(const StudySpec& spec);

}  // namespace terracal::app
