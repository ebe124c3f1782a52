#include "apps/campaign_db.hpp"

#include <sqlite3.h>

#include <fmt/format.h>

#include "core/errors.hpp"

namespace terracal::app {
namespace {

// A prepared statement, finalised on every path.
class Statement {
 public:
  Statement(sqlite3* db, const char* sql, const std::string& path) : db_(db) {
    if (sqlite3_prepare_v2(db, sql, -1, &st_, nullptr) != SQLITE_OK)
      throw RunError(fmt::format("{}: {}", path, sqlite3_errmsg(db)));
  }
  ~Statement() { sqlite3_finalize(st_); }
  Statement& bind(int i, const std::string& v) {
    sqlite3_bind_text(st_, i, v.c_str(), -1, SQLITE_TRANSIENT);
    return *this;
  }
  Statement& bind(int i, double v) {
    sqlite3_bind_double(st_, i, v);
    return *this;
  }
  int step() { return sqlite3_step(st_); }
  std::string text(int c) const {
    const auto* t = sqlite3_column_text(st_, c);
    return t ? reinterpret_cast<const char*>(t) : "";
  }
  double real(int c) const { return sqlite3_column_double(st_, c); }

 private:
  sqlite3* db_;
  sqlite3_stmt* st_ = nullptr;
};

}  // namespace

CampaignDb::CampaignDb(const std::string& path) : path_(path) {
  if (sqlite3_open(path.c_str(), &db_) != SQLITE_OK) {
    const std::string why = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    throw RunError(fmt::format("{}: cannot open the campaign database: {}", path, why));
  }
  sqlite3_busy_timeout(db_, 60000);  // another process (a rank, a --status) may hold the lock briefly
  exec("PRAGMA journal_mode=WAL");
  exec("PRAGMA synchronous=FULL");
  exec("CREATE TABLE IF NOT EXISTS jobs (seq INTEGER PRIMARY KEY AUTOINCREMENT, key TEXT UNIQUE NOT NULL, "
       "stage TEXT, label TEXT, dir TEXT, state TEXT, error TEXT, wall_seconds REAL, updated TEXT, worker TEXT)");
}

CampaignDb::~CampaignDb() { sqlite3_close(db_); }

void CampaignDb::exec(const std::string& sql) const {
  char* err = nullptr;
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &err) != SQLITE_OK) {
    const std::string why = err ? err : "unknown error";
    sqlite3_free(err);
    throw RunError(fmt::format("{}: {}", path_, why));
  }
}

void CampaignDb::add(const std::string& key, const std::string& stage, const std::string& label,
                     const std::string& dir) {
  Statement s(db_,
              "INSERT OR IGNORE INTO jobs (key, stage, label, dir, state, error, wall_seconds, updated) "
              "VALUES (?, ?, ?, ?, 'queued', '', 0, strftime('%Y-%m-%dT%H:%M:%SZ','now'))",
              path_);
  s.bind(1, key).bind(2, stage).bind(3, label).bind(4, dir);
  if (s.step() != SQLITE_DONE) throw RunError(fmt::format("{}: {}", path_, sqlite3_errmsg(db_)));
}

void CampaignDb::set_state(const std::string& key, const std::string& state, const std::string& error,
                           double wall_seconds, const std::string& worker) {
  Statement s(db_,
              "UPDATE jobs SET state = ?, error = ?, wall_seconds = ?, worker = ?, "
              "updated = strftime('%Y-%m-%dT%H:%M:%SZ','now') WHERE key = ?",
              path_);
  s.bind(1, state).bind(2, error).bind(3, wall_seconds).bind(4, worker).bind(5, key);
  if (s.step() != SQLITE_DONE) throw RunError(fmt::format("{}: {}", path_, sqlite3_errmsg(db_)));
}

std::string CampaignDb::state(const std::string& key) const {
  Statement s(db_, "SELECT state FROM jobs WHERE key = ?", path_);
  s.bind(1, key);
  return s.step() == SQLITE_ROW ? s.text(0) : "";
}

std::vector<JobRow> CampaignDb::rows() const {
  Statement s(db_,
              "SELECT key, stage, label, dir, state, error, worker, wall_seconds, updated FROM jobs ORDER BY seq",
              path_);
  std::vector<JobRow> out;
  while (s.step() == SQLITE_ROW)
    out.push_back({s.text(0), s.text(1), s.text(2), s.text(3), s.text(4), s.text(5), s.text(6), s.real(7), s.text(8)});
  return out;
}

}  // namespace terracal::app
