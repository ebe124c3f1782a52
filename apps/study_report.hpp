#pragma once
// A study's results (docs/study.md): DIR/report.md, DIR/<study>.csv and DIR/<study>.png, from the
// runs' wheel.csv or trajectory.csv, their run.json and the job table.
//   accuracy-cost: each run's RMSE against the reference (drawbar pull, torque, sinkage over the
//     slips, in % of the reference's largest value) next to its wall time, with the Pareto front;
//   stability: each run's verdict: stable, failed (the command's exit and message), non-finite,
//     blew up (sinkage past the wheel's radius, drawbar pull or torque above 5 x the wheel's weight
//     (x radius)), or unsteady (drawbar pull's standard deviation above the weight); a vehicle's:
//     non-finite, blew up, rolled over; a run of a `step` sweep that ends more than 25 % from the base
//     run has drifted;
//   effects: each variant's wall time against the base's and how far it moves the results.
#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace terracal::app {

struct StudySpec;
struct CampaignJob;
class CampaignDb;

// Verdicts of the stability study.
inline constexpr const char* kStable = "stable";

// The verdict on one run from its job's state and error and its wheel.csv's columns (the radius and
// weight of its wheel under its gravity).
std::string stability_verdict(const std::string& state, const std::string& error,
                              const std::map<std::string, std::vector<double>>& wheel, double radius, double weight);

// The same for a vehicle's trajectory.csv: non-finite, blew up (|vx| above 100 m/s, |yaw rate| above
// 10 rad/s, |ay| above 100 m/s^2), rolled over (|roll| above 1 rad), or (the full vehicle, whose
// run.json gives its largest constraint error; NAN for a ROM) constraint drift above
// kConstraintDrift.
inline constexpr double kConstraintDrift = 1e-3;  // m or rad; steady runs: 1e-7 to 1e-5
std::string vehicle_verdict(const std::string& state, const std::string& error,
                            const std::map<std::string, std::vector<double>>& trajectory,
                            double max_constraint_violation = NAN);

void write_study_report(const std::string& dir, const StudySpec& spec, const std::vector<CampaignJob>& jobs,
                        const CampaignDb& db);

}  // namespace terracal::app
