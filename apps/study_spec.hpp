#pragma once
// `terracal study`'s spec (docs/study.md): the mission's three demands as runs of one solver (the
// single-wheel rig for crm, scm and wong-reece; a manoeuvre for rom and vehicle), each run a job of a
// campaign (resumable, MPI-ready):
//   accuracy-cost  each fidelity knob from coarse to fine, the others at their finest; the reference
//                  is every knob at its finest, or (key `reference`) the base with the reference's own
//                  options, each knob's runs then being the base with that knob's value;
//   stability      sweeps of step, gravity, stiffness, slip and more, each alone from the base
//                  settings, plus a wheel at standstill;
//   effects        each effect variant against the base settings.
// A spec holds the scene (wheel and soil, or vehicle and manoeuvre), the base options and each
// study's lists; every key is optional and replaces the embedded default's for the solver, so
// `--spec` names only what it changes.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/campaign_spec.hpp"

namespace terracal::app {

enum class StudyKind { kAccuracyCost, kStability, kEffects };
inline const std::vector<std::string> kStudyKinds = {"accuracy-cost", "stability", "effects"};
std::string study_kind_name(StudyKind k);

enum class StudySolver { kCrm, kScm, kWongReece, kRom, kVehicle };
inline const std::vector<std::string> kStudySolvers = {"crm", "scm", "wong-reece", "rom", "vehicle"};
std::string study_solver_name(StudySolver s);
// The command a solver's runs are: "wheel" (crm, scm, wong-reece), "rom" or "vehicle".
std::string study_command(StudySolver s);

// One single-wheel run of a study.
struct StudyRun {
  std::string group;  // the knob, the sweep or the effect variant's name; "reference" / "base"
  std::string label;  // folder-safe: "grid_0.005"
  double value = 0;   // the knob's or the sweep's value (0 for effects, the reference, standstill and text values)
  std::string value_text;          // the value as given ("0.005", "11dof")
  nlohmann::ordered_json options;  // the command's options (base with the run's own over them)
  // The scene: option -> content, written to a file the option names (an object), or given as it is
  // (a string: a preset). Wheel rig: wheel, scm | soil; rom, vehicle: vehicle, maneuver.
  nlohmann::ordered_json scene;
  bool reference = false;  // accuracy-cost: the reference; stability, effects: the base
};

struct StudySpec {
  StudyKind kind = StudyKind::kAccuracyCost;
  StudySolver solver = StudySolver::kScm;
  // crm and scm: the rig the runs use, "wheel" (the default) or "bevameter" (key `rig`: plate tests,
  // compared on their loading curves).
  std::string rig = "wheel";
  std::string source;            // the spec file, or "the embedded default"
  nlohmann::ordered_json merged;  // the default with the file's keys over it: what ran (DIR/spec.json)
  std::vector<StudyRun> runs;    // the reference / base first
};

// The command the spec's runs are: study_command(solver), or "bevameter" for the bevameter rig.
std::string study_command(const StudySpec& s);

// The embedded default spec of a solver (and rig: "wheel" or, for crm and scm, "bevameter").
nlohmann::ordered_json default_study_spec(StudySolver solver, const std::string& rig = "wheel");

// Reads `path` (empty: the default alone) over the solver's default and makes the runs. Throws
// InputError naming the file, the key and the value for an unknown key, a wheel option the wheel
// command does not take or refuses, an empty or unordered list, a soil without the value a sweep
// scales, or a study the solver has nothing for (Wong-Reece has no effects).
StudySpec read_study_spec(StudyKind kind, StudySolver solver, const std::string& path);

// The runs as campaign jobs (stage: the study's name); the scene's objects are written into
// DIR/inputs/ before a job starts.
std::vector<CampaignJob> study_jobs(const StudySpec& spec);

}  // namespace terracal::app
