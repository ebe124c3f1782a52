#pragma once
// A campaign's state in DIR/campaign.sqlite (SQLite): one row per job with its state (queued, running,
// done, failed), error, wall time and when it changed. Every change of a job's state is one
// transaction, so a process killed at any moment leaves the table as of its last change.
#include <string>
#include <vector>

struct sqlite3;

namespace terracal::app {

struct JobRow {
  std::string key, stage, label, dir, state, error;
  std::string worker;  // who ran it last: "local", or "rank 2 (GPU 1)" under MPI
  double wall_seconds = 0;
  std::string updated;  // UTC, ISO 8601
};

class CampaignDb {
 public:
  // Opens (creating) the database; throws RunError when SQLite cannot.
  explicit CampaignDb(const std::string& path);
  ~CampaignDb();
  CampaignDb(const CampaignDb&) = delete;
  CampaignDb& operator=(const CampaignDb&) = delete;

  // Adds the job as queued unless its key is known.
  void add(const std::string& key, const std::string& stage, const std::string& label, const std::string& dir);
  void set_state(const std::string& key, const std::string& state, const std::string& error = "",
                 double wall_seconds = 0, const std::string& worker = "");
  std::string state(const std::string& key) const;  // "" for an unknown key
  std::vector<JobRow> rows() const;                 // in the order they were added

 private:
  void exec(const std::string& sql) const;
  sqlite3* db_ = nullptr;
  std::string path_;
};

}  // namespace terracal::app
