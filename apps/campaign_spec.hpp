#pragma once
// A campaign's spec (docs/campaign.md): soils x gravities x wheels, each taken through the stages
// bevameter -> calibrate -> wheel (the calibrated set) beside wheel_reference (the soil itself), and
// on to the vehicles: wheel_table (the calibrated set tabulated for a wheel) -> rom (a reduced-order
// vehicle driving on that table); and the jobs it makes. Every job is one terracal command run in its own process; its key hashes the
// command, the contents of its input files and the keys of the jobs it reads, so a finished job is
// never recomputed and a changed input reruns only what depends on it.
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace terracal::app {

inline const std::vector<std::string> kCampaignStages = {"bevameter", "calibrate",   "wheel",
                                                          "wheel_reference", "wheel_table", "rom"};

struct CampaignSoil {
  std::string name;
  std::string scm;  // SCM set (file), the quick campaign's soil; or
  std::string crm;  // CRM material (file)
};

struct CampaignWheel {
  std::string name, file;
};

// A vehicle driven on each entry's soil: a ROM (options.rom.model, default 18dof) on the wheel table
// of one of the campaign's wheels (its tire).
struct CampaignVehicle {
  std::string name;
  std::string vehicle;   // preset or file
  std::string maneuver;  // file
  std::string wheel;     // the name of the wheel whose table it drives on
};

struct CampaignSpec {
  std::string name;
  std::vector<CampaignSoil> soils;
  std::vector<double> gravities;  // [m/s^2], magnitude, pointing down
  std::vector<CampaignWheel> wheels;
  std::vector<CampaignVehicle> vehicles;
  std::vector<std::string> stages;                        // in kCampaignStages order
  std::map<std::string, nlohmann::ordered_json> options;  // per stage: option name (no dashes) -> value
};

struct CampaignJob {
  std::string key;    // 32 hex digits
  std::string stage;  // one of kCampaignStages
  std::string label;  // "sand_g9.81" or "sand_g9.81_rover"
  std::string dir;    // relative to the campaign folder: jobs/<stage>/<label>-<key prefix>
  std::string command;            // the terracal command
  std::vector<std::string> args;  // its arguments, --out left out
  std::vector<int> needs;         // indices of the jobs whose outputs it reads
  int group = 0;                  // soil x gravity index: a group's jobs stay in one shard
  // Files the job needs written into the campaign folder first (path relative to it, content): a CRM
  // material with the entry's gravity put in.
  std::vector<std::pair<std::string, std::string>> writes;
  // A command whose --out names a file (wheel-table): that file's name in the job's folder.
  std::string out_file;
};

// Reads and validates SPEC.json: unknown keys, empty grids, missing files, duplicate names, a stage
// whose input stage is left out and options the stage's command does not take (or values it refuses)
// throw InputError naming the file, the key and the value. Paths in the spec are relative to it.
CampaignSpec read_campaign_spec(const std::string& path);

// The jobs in run order (a job after every job it needs); jobs that would be identical (the same
// bevameter run for every wheel) appear once.
std::vector<CampaignJob> campaign_jobs(const CampaignSpec& spec);

// Appends `job` to `jobs` with its key (its stage, arguments, the bytes of `files` and of the files
// it writes, the keys of the jobs it needs, the program version) and its folder
// (jobs/<stage>/<label>-<key prefix>); returns its index. Every maker of jobs (campaign, study) adds
// them through here.
int add_job(std::vector<CampaignJob>& jobs, CampaignJob job, const std::vector<std::string>& files);

// The arguments a job runs with: its args, with "--out <folder>". "@0/" in them stands for the folder
// of the first job it needs, "@out/" for the campaign folder.
std::vector<std::string> job_command_line(const CampaignJob& job, const std::string& out_dir);

}  // namespace terracal::app
