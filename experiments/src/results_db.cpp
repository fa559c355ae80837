// The results database (docs/file_formats.md): its schema, how a file is opened and recognised as
// CoverBench's, its transactions, and the provenance an experiment stores. What is written to it
// is in results_db_write.cpp, what is read from it in results_db_read.cpp.
#include "coverbench/results_db.hpp"

#include <sqlite3.h>
#include <sys/utsname.h>
#include <unistd.h>

#include <ctime>
#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>
#include <thread>

#include "coverbench/build_identity.hpp"
#include "run_columns.hpp"
#include "sqlite_statement.hpp"

namespace coverbench {
namespace {

/// Marks a database as CoverBench's (PRAGMA application_id; "CvBn"), and its schema version.
/// Schema 2: run keys with the planner's version and code identity; runs measured in child
/// processes (rusage), every repetition's time, provenance per experiment. Tables added since,
/// without a new version because an older build reads such a database correctly by ignoring them:
/// experiment_shard (which shard an experiment is), merged_shards (what a merge was made of) and
/// run_options (the vehicle and transit planner of each run that has another than holonomic and
/// visibility: an older build knows only those, stores and reads none, and would draw a gantry
/// run's lifted moves as transits); replans and replan_figures (docs/replanning.md: a run's
/// repairs after surprise obstacles, only for experiments with replanning; an older build ignores
/// them and still reads every run correctly); run_car (a car's turn radius and reversing, beside
/// its run_options row; an older build would read such a run as a holonomic one with arcs);
/// run_profile (the tool's flux profile of each run that has one, docs/deposition.md: an older
/// build lists such a run without it; a database without the table reads as disk tools without
/// a profile); run_profile_target (the profile's target thickness, for a run whose profile has
/// one: an older build lists and scores such a run against the mean); run_profile_flow (the
/// profile's flow for a run whose gun's flow follows the speed: an older build would list such a
/// run as a constant flow's; a database without the table reads as constant flows); run_tool_shape (the tool's
/// shape of each run whose tool is not a disk, docs/metrics.md#tool-shapes: a database without
/// the table reads as disk tools; an older build would read a line tool's run as a disk's);
/// run_tool_depth (a rectangle tool's depth d, for each run whose tool is a rectangle). Run
/// fields added since (stderr_tail) are columns added to an older database when it is written
/// (addMissingRunColumns; its runs read as empty) and read as empty where a database opened
/// read-only lacks them; an older build ignores them.
constexpr long long kApplicationId = 0x4376424e;
constexpr long long kSchemaVersion = 2;

const char* const kSchema = R"sql(
CREATE TABLE IF NOT EXISTS experiments (
  id INTEGER PRIMARY KEY, name TEXT NOT NULL, config_path TEXT, config_text TEXT NOT NULL,
  config_hash TEXT NOT NULL, baseline TEXT NOT NULL, command_line TEXT NOT NULL,
  git_revision TEXT NOT NULL, git_diff_sha256 TEXT NOT NULL, compiler TEXT NOT NULL, build_type TEXT NOT NULL,
  build_flags TEXT NOT NULL, host TEXT NOT NULL, cpu TEXT NOT NULL, cores INTEGER NOT NULL, os TEXT NOT NULL,
  memory_bytes REAL, workers INTEGER NOT NULL, started_at TEXT NOT NULL, finished_at TEXT,
  runs_total INTEGER, runs_executed INTEGER, runs_skipped INTEGER, runs_reused INTEGER, rerun_reasons TEXT);
CREATE TABLE IF NOT EXISTS experiment_datasets (
  experiment_id INTEGER NOT NULL, position INTEGER NOT NULL, label TEXT NOT NULL, source TEXT NOT NULL,
  walls INTEGER NOT NULL, sha256 TEXT NOT NULL, PRIMARY KEY (experiment_id, position)) WITHOUT ROWID;
CREATE TABLE IF NOT EXISTS walls (
  hash TEXT PRIMARY KEY, name TEXT NOT NULL, content TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS experiment_walls (
  experiment_id INTEGER NOT NULL, wall_hash TEXT NOT NULL, dataset TEXT NOT NULL,
  PRIMARY KEY (experiment_id, wall_hash)) WITHOUT ROWID;
CREATE TABLE IF NOT EXISTS planner_configs (
  id TEXT PRIMARY KEY, planner TEXT NOT NULL, params TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS experiment_planners (
  experiment_id INTEGER NOT NULL, position INTEGER NOT NULL, config_id TEXT NOT NULL, label TEXT NOT NULL,
  PRIMARY KEY (experiment_id, position)) WITHOUT ROWID;
CREATE TABLE IF NOT EXISTS experiment_runs (
  experiment_id INTEGER NOT NULL, run_key TEXT NOT NULL, PRIMARY KEY (experiment_id, run_key)) WITHOUT ROWID;
CREATE TABLE IF NOT EXISTS runs (
  key TEXT PRIMARY KEY, base_key TEXT NOT NULL, wall_hash TEXT NOT NULL, config_id TEXT NOT NULL,
  planner_version TEXT NOT NULL, code_sha256 TEXT NOT NULL, build TEXT NOT NULL,
  tool_width REAL NOT NULL, clearance REAL NOT NULL, seed INTEGER NOT NULL, repetitions INTEGER NOT NULL,
  @RUN_FIELDS@, finished_at TEXT NOT NULL);
CREATE INDEX IF NOT EXISTS runs_by_base_key ON runs (base_key);
CREATE TABLE IF NOT EXISTS run_repetitions (
  run_key TEXT NOT NULL, repetition INTEGER NOT NULL, plan_time_ms REAL NOT NULL,
  PRIMARY KEY (run_key, repetition)) WITHOUT ROWID;
CREATE TABLE IF NOT EXISTS metrics (
  run_key TEXT NOT NULL, position INTEGER NOT NULL, name TEXT NOT NULL, value REAL,
  PRIMARY KEY (run_key, name)) WITHOUT ROWID;
CREATE TABLE IF NOT EXISTS planner_stats (
  run_key TEXT NOT NULL, name TEXT NOT NULL, value REAL, PRIMARY KEY (run_key, name)) WITHOUT ROWID;
CREATE TABLE IF NOT EXISTS paths (
  run_key TEXT PRIMARY KEY, encoding TEXT NOT NULL, waypoints INTEGER NOT NULL, data BLOB NOT NULL);
CREATE TABLE IF NOT EXISTS planner_timings (
  run_key TEXT NOT NULL, name TEXT NOT NULL, ms REAL, PRIMARY KEY (run_key, name)) WITHOUT ROWID;
CREATE TABLE IF NOT EXISTS run_options (
  run_key TEXT PRIMARY KEY, vehicle TEXT NOT NULL, lift_s REAL NOT NULL, lower_s REAL NOT NULL,
  transit TEXT NOT NULL, transit_iterations INTEGER NOT NULL);
CREATE TABLE IF NOT EXISTS run_car (
  run_key TEXT PRIMARY KEY, turn_radius REAL NOT NULL, reverse INTEGER NOT NULL);
CREATE TABLE IF NOT EXISTS run_profile (
  run_key TEXT PRIMARY KEY, kind TEXT NOT NULL, sigma REAL NOT NULL, beta REAL NOT NULL, rate REAL NOT NULL,
  depth REAL NOT NULL);
CREATE TABLE IF NOT EXISTS run_profile_target (
  run_key TEXT PRIMARY KEY, target REAL NOT NULL);
CREATE TABLE IF NOT EXISTS run_profile_flow (
  run_key TEXT PRIMARY KEY, flow TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS run_tool_shape (
  run_key TEXT PRIMARY KEY, shape TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS run_tool_depth (
  run_key TEXT PRIMARY KEY, depth REAL NOT NULL);
CREATE TABLE IF NOT EXISTS replans (
  run_key TEXT NOT NULL, position INTEGER NOT NULL, fraction REAL NOT NULL, repair TEXT NOT NULL,
  obstacles INTEGER NOT NULL, requested INTEGER NOT NULL, obstacles_json TEXT NOT NULL, status TEXT NOT NULL,
  reason TEXT NOT NULL, valid INTEGER NOT NULL, repair_ms REAL, path BLOB, cut_waypoint INTEGER NOT NULL,
  PRIMARY KEY (run_key, position)) WITHOUT ROWID;
CREATE TABLE IF NOT EXISTS replan_figures (
  run_key TEXT NOT NULL, position INTEGER NOT NULL, name TEXT NOT NULL, value REAL,
  PRIMARY KEY (run_key, position, name)) WITHOUT ROWID;
CREATE TABLE IF NOT EXISTS experiment_shard (
  experiment_id INTEGER PRIMARY KEY, shard_index INTEGER NOT NULL, shard_count INTEGER NOT NULL,
  config_runs INTEGER NOT NULL);
CREATE TABLE IF NOT EXISTS merged_shards (
  experiment_id INTEGER NOT NULL, shard_index INTEGER NOT NULL, shard_count INTEGER NOT NULL,
  source TEXT NOT NULL, runs INTEGER NOT NULL, runs_sha256 TEXT NOT NULL, host TEXT NOT NULL,
  workers INTEGER NOT NULL, started_at TEXT NOT NULL, finished_at TEXT,
  PRIMARY KEY (experiment_id, shard_index, source)) WITHOUT ROWID;
)sql";

/// The schema: kSchema with the run fields' columns (kRunFields, after the run's context).
std::string schemaSql() {
  std::string fields;
  for (const RunField& f : kRunFields)
    if (std::string_view(f.name) != "key") fields += (fields.empty() ? "" : ", ") + std::string(f.name) + " " + sqlType(f);
  std::string s = kSchema;
  s.replace(s.find("@RUN_FIELDS@"), 12, fields);
  return s;
}

/// The tables every CoverBench database has had since the first schema (before application_id
/// was set): how a database written by an earlier build is recognised.
const char* const kCoreTables[] = {"experiments", "walls", "runs", "metrics", "paths"};

}  // namespace

std::string utcNow() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

Provenance currentProvenance(unsigned workers, const std::string& command_line) {
  Provenance p;
  const BuildIdentity& b = buildIdentity();
  p.git_revision = b.git_revision;
  p.git_diff_sha256 = b.dirty_diff_sha256;
  p.compiler = b.compiler;
  p.build_type = b.build_type;
  p.build_flags = b.flags;
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);)
    if (line.rfind("model name", 0) == 0) {
      p.cpu = line.substr(line.find(':') + 2);
      break;
    }
  utsname u{};
  if (::uname(&u) == 0) {
    p.host = u.nodename;
    p.os = std::string(u.sysname) + " " + u.release + " " + u.machine;
  }
  std::ifstream release("/etc/os-release");
  for (std::string line; std::getline(release, line);)
    if (line.rfind("PRETTY_NAME=", 0) == 0) {
      std::string name = line.substr(12);
      if (name.size() >= 2 && name.front() == '"') name = name.substr(1, name.size() - 2);
      p.os = name + ", " + p.os;
    }
  p.cores = std::thread::hardware_concurrency();
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  if (pages > 0 && page > 0) p.memory_bytes = static_cast<double>(pages) * static_cast<double>(page);
  p.command_line = command_line;
  p.started_at = utcNow();
  p.workers = workers;
  return p;
}

ResultsDb::ResultsDb(const std::string& path, Mode mode) : file_(path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const bool exists = fs::exists(path, ec);
  if (exists && fs::is_directory(path, ec)) throw InputError(path, "(database)", "is a folder, not a database file");
  if (mode == Mode::ReadOnly && !exists) throw InputError(path, "(file)", "does not exist");
  // Nothing is written to a file before it is known to be CoverBench's (or new and empty).
  const bool empty = !exists || fs::file_size(path, ec) == 0;
  if (mode == Mode::ReadOnly && empty)
    throw InputError(path, "(database)", "is not a CoverBench results database (an empty file)");
  // SQLite makes -wal and -shm files beside a WAL database it opens, even to read: a file that is
  // refused keeps only what it had beside it.
  const bool had_wal = fs::exists(path + "-wal", ec), had_shm = fs::exists(path + "-shm", ec);
  const int flags = mode == Mode::ReadOnly ? SQLITE_OPEN_READONLY : SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE;
  if (sqlite3_open_v2(path.c_str(), &db_, flags, nullptr) != SQLITE_OK) {
    const std::string why = db_ ? sqlite3_errmsg(db_) : "out of memory";
    sqlite3_close(db_);
    db_ = nullptr;
    throw InputError(path, "(database)", "cannot be opened: " + why);
  }
  sqlite3_busy_timeout(db_, 10000);
  try {
    const Marks marks = empty ? Marks{} : checkOwnership(mode);
    if (mode == Mode::ReadWrite) {
      // The tables and the marks in one transaction: a process killed while creating a database
      // leaves either no table or all of them, never a half schema that would be refused later.
      // A database of this schema is not written at all (its header's change counter stays).
      exec("PRAGMA journal_mode = WAL; PRAGMA synchronous = NORMAL;");  // not allowed inside a transaction
      exec("BEGIN IMMEDIATE");
      try {
        exec(schemaSql());
        addMissingRunColumns();
        if (marks.application_id != kApplicationId || marks.version != kSchemaVersion)
          exec("PRAGMA application_id = " + std::to_string(kApplicationId) + "; PRAGMA user_version = " +
               std::to_string(kSchemaVersion) + ";");
        exec("COMMIT");
      } catch (...) {
        rollback();
        throw;
      }
    }
  } catch (...) {  // a constructor that throws runs no destructor: close the connection here
    sqlite3_close(db_);
    db_ = nullptr;
    if (!had_wal) fs::remove(path + "-wal", ec);
    if (!had_shm) fs::remove(path + "-shm", ec);
    throw;
  }
}

std::set<std::string> ResultsDb::runColumns() { return tableColumns(db_, "runs", file_); }

void ResultsDb::addMissingRunColumns() {
  // A field added to the run record after this database was made: its runs have no value (NULL).
  const std::set<std::string> columns = runColumns();
  for (const RunField& f : kRunFields)
    if (!columns.count(f.name)) {
      const bool text = f.type == RunFieldType::Text || f.type == RunFieldType::Status;
      exec(std::string("ALTER TABLE runs ADD COLUMN ") + f.name +
           (text ? " TEXT NOT NULL DEFAULT ''" : f.type == RunFieldType::Real ? " REAL" : " INTEGER"));
    }
}

std::string ResultsDb::runFieldSelect(const std::string& alias) {
  return runFieldExpressions(runColumns(), alias, [](const RunField&) { return true; });
}

ResultsDb::Marks ResultsDb::checkOwnership(Mode mode) {
  Marks marks;
  std::set<std::string> tables;
  try {
    Statement a(db_, "PRAGMA application_id", file_);
    if (a.step()) marks.application_id = a.columnInt(0);
    Statement v(db_, "PRAGMA user_version", file_);
    if (v.step()) marks.version = v.columnInt(0);
    Statement t(db_, "SELECT name FROM sqlite_master WHERE type = 'table'", file_);
    while (t.step()) tables.insert(t.columnText(0));
  } catch (const InputError& e) {
    throw InputError(file_, "(database)", "is not a CoverBench results database (" + e.problem() + ")");
  }
  // No table and no mark: a database created (journal mode set) by a process killed before its
  // first transaction committed, or any empty one. It holds nothing to lose: take it as new; but
  // there is nothing in it to read.
  if (marks.application_id == 0 && tables.empty()) {
    if (mode == Mode::ReadOnly)
      throw InputError(file_, "(database)", "is not a CoverBench results database (an SQLite database with no tables)");
    return marks;
  }
  const long long application_id = marks.application_id, version = marks.version;
  bool legacy = application_id == 0;
  for (const char* table : kCoreTables) legacy = legacy && tables.count(table);
  if (application_id != kApplicationId && !legacy)
    throw InputError(file_, "(database)", "is not a CoverBench results database; nothing was changed");
  if (version > kSchemaVersion)
    throw InputError(file_, "(database)",
                     "has schema version " + std::to_string(version) + ", newer than this build's " +
                         std::to_string(kSchemaVersion) + ": use a newer coverbench");
  if (version < kSchemaVersion)  // never misread: its runs have keys of another scheme
    throw InputError(file_, "(database)",
                     "was written by an older CoverBench (schema " + std::to_string(version) + "; this build reads " +
                         std::to_string(kSchemaVersion) +
                         "), whose run keys did not include the planners' code: run the experiment into a new output "
                         "folder (or move this one away)");
  return marks;
}

void ResultsDb::rollback() noexcept {
  for (auto& entry : prepared_) entry.second->reset();  // a statement left stepping by the failure
  // After a failed COMMIT (a full disk, say) SQLite may have rolled back already: then there is
  // nothing to undo, and ROLLBACK's own error must not hide the real one.
  if (!sqlite3_get_autocommit(db_)) sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
}

void ResultsDb::limitPagesForTesting(long long pages) {
  exec("PRAGMA max_page_count = " + std::to_string(pages));
}

ResultsDb::~ResultsDb() {
  prepared_.clear();
  if (db_) sqlite3_close(db_);
}

Statement& ResultsDb::prepared(const std::string& sql) {
  std::unique_ptr<Statement>& s = prepared_[sql];
  if (!s) s = std::make_unique<Statement>(db_, sql, file_);
  s->reset();  // a use that threw may have left it stepped or bound
  return *s;
}

void ResultsDb::exec(const std::string& sql) {
  char* error = nullptr;
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &error) != SQLITE_OK) {
    const std::string why = error ? error : "unknown error";
    sqlite3_free(error);
    throw InputError(file_, "(database)", why);
  }
}

}  // namespace coverbench
