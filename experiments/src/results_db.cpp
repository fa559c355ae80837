#include "coverbench/results_db.hpp"

#include <nlohmann/json.hpp>
#include <sqlite3.h>
#include <sys/utsname.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <thread>

#include "coverbench/build_identity.hpp"
#include "coverbench/hash.hpp"
#include "coverbench/metric_spec.hpp"
#include "coverbench/wall_file.hpp"
#include "run_columns.hpp"
#include "sqlite_statement.hpp"
#include <stdexcept>

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
/// its run_options row; an older build would read such a run as a holonomic one with arcs). Run
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

/// The columns of run_options a LEFT JOIN selects (alias o), in the order storedOptions reads.
constexpr const char* kOptionColumns =
    "o.vehicle, o.lift_s, o.lower_s, o.transit, o.transit_iterations, car.turn_radius, car.reverse";
/// The joins kOptionColumns needs (after the runs table, alias r).
constexpr const char* kOptionJoins = " LEFT JOIN run_options o ON o.run_key = r.key LEFT JOIN run_car car ON car.run_key = r.key ";
/// The vehicle and transit planner in columns i .. i + 4 (kOptionColumns): holonomic and
/// visibility when the run has no row in run_options.
void storedOptions(const Statement& s, int i, VehicleModel& vehicle, TransitSpec& transit) {
  vehicle = VehicleModel{};
  transit = TransitSpec{};
  if (s.columnNull(i)) return;
  if (!parseVehicleKind(s.columnText(i), vehicle.kind)) throw std::runtime_error("run_options: unknown vehicle " + s.columnText(i));
  vehicle.lift_s = s.columnReal(i + 1);
  vehicle.lower_s = s.columnReal(i + 2);
  transit.planner = s.columnText(i + 3);
  transit.iterations = s.columnInt(i + 4);
  if (!s.columnNull(i + 5)) {
    vehicle.turn_radius = s.columnReal(i + 5);
    vehicle.reverse = s.columnInt(i + 6) != 0;
  }
}

std::string gibibytes(double bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f GiB", bytes / (1024.0 * 1024 * 1024));
  return buf;
}

/// The resolved parameters as a JSON object, numbers with full precision (paramsJson reads it).
std::string paramsText(const PlannerConfig& pc) {
  return paramsJson(pc.params).dump();
}

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
  // After a failed COMMIT (a full disk, say) SQLite may have rolled back already: then there is
  // nothing to undo, and ROLLBACK's own error must not hide the real one.
  if (!sqlite3_get_autocommit(db_)) sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
}

void ResultsDb::limitPagesForTesting(long long pages) {
  exec("PRAGMA max_page_count = " + std::to_string(pages));
}

ResultsDb::~ResultsDb() {
  if (db_) sqlite3_close(db_);
}

void ResultsDb::exec(const std::string& sql) {
  char* error = nullptr;
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &error) != SQLITE_OK) {
    const std::string why = error ? error : "unknown error";
    sqlite3_free(error);
    throw InputError(file_, "(database)", why);
  }
}

long long ResultsDb::beginExperiment(const ExperimentConfig& config, const Provenance& prov,
                                     const std::vector<WallEntry>& walls, const std::vector<std::string>& run_keys,
                                     const ShardRecord* shard) {
  exec("BEGIN IMMEDIATE");
  try {
    Statement e(db_,
                "INSERT INTO experiments (name, config_path, config_text, config_hash, baseline, command_line, "
                "git_revision, git_diff_sha256, compiler, build_type, build_flags, host, cpu, cores, os, memory_bytes, "
                "workers, started_at, runs_total) VALUES (?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?)",
                file_);
    e.text(1, config.name).text(2, config.path).text(3, config.text).text(4, config.hash).text(5, config.baseline);
    e.text(6, prov.command_line).text(7, prov.git_revision).text(8, prov.git_diff_sha256).text(9, prov.compiler);
    e.text(10, prov.build_type).text(11, prov.build_flags).text(12, prov.host).text(13, prov.cpu);
    e.integer(14, prov.cores).text(15, prov.os).real(16, prov.memory_bytes).integer(17, prov.workers);
    e.text(18, prov.started_at).integer(19, static_cast<long long>(run_keys.size())).run();
    const long long id = sqlite3_last_insert_rowid(db_);
    Statement w(db_, "INSERT OR IGNORE INTO walls (hash, name, content) VALUES (?,?,?)", file_);
    Statement ew(db_, "INSERT OR IGNORE INTO experiment_walls (experiment_id, wall_hash, dataset) VALUES (?,?,?)", file_);
    for (const WallEntry& wall : walls) {
      if (!shard || shard->wall_hashes.count(wall.hash)) w.text(1, wall.hash).text(2, wall.wall.name).text(3, wall.json).run();
      ew.integer(1, id).text(2, wall.hash).text(3, wall.dataset).run();
    }
    // Each dataset's identity: the SHA-256 of its walls' content hashes, in order.
    Statement ed(db_,
                 "INSERT INTO experiment_datasets (experiment_id, position, label, source, walls, sha256) VALUES "
                 "(?,?,?,?,?,?)",
                 file_);
    for (std::size_t i = 0; i < config.datasets.size(); ++i) {
      const DatasetSpec& d = config.datasets[i];
      std::string hashes;
      long long count = 0;
      for (const WallEntry& wall : walls)
        if (wall.dataset == d.label) hashes += wall.hash + "\n", ++count;
      const std::string source = d.kind == DatasetSpec::Kind::Family ? "family " + d.family + " count " +
                                                                           std::to_string(d.count) + " seed " +
                                                                           std::to_string(d.seed)
                                 : d.kind == DatasetSpec::Kind::Suite ? "suite " + d.family
                                                                      : "folder " + d.folder;
      ed.integer(1, id).integer(2, static_cast<long long>(i)).text(3, d.label).text(4, source).integer(5, count);
      ed.text(6, sha256Hex(hashes)).run();
    }
    Statement p(db_, "INSERT OR IGNORE INTO planner_configs (id, planner, params) VALUES (?,?,?)", file_);
    Statement ep(db_, "INSERT INTO experiment_planners (experiment_id, position, config_id, label) VALUES (?,?,?,?)", file_);
    for (std::size_t i = 0; i < config.planners.size(); ++i) {
      const PlannerConfig& pc = config.planners[i];
      p.text(1, pc.id).text(2, pc.planner).text(3, paramsText(pc)).run();
      ep.integer(1, id).integer(2, static_cast<long long>(i)).text(3, pc.id).text(4, pc.label).run();
    }
    Statement er(db_, "INSERT OR IGNORE INTO experiment_runs (experiment_id, run_key) VALUES (?,?)", file_);
    for (const std::string& key : run_keys) er.integer(1, id).text(2, key).run();
    if (shard) {
      Statement es(db_, "INSERT INTO experiment_shard (experiment_id, shard_index, shard_count, config_runs) VALUES (?,?,?,?)",
                   file_);
      es.integer(1, id).integer(2, shard->shard.index).integer(3, shard->shard.count);
      es.integer(4, static_cast<long long>(shard->config_runs)).run();
    }
    exec("COMMIT");
    return id;
  } catch (...) {
    rollback();
    throw;
  }
}

std::vector<ResultsDb::StoredKey> ResultsDb::storedKeys() {
  std::vector<StoredKey> out;
  Statement s(db_, "SELECT key, base_key, planner_version, code_sha256, status FROM runs", file_);
  while (s.step()) {
    StoredKey k{s.columnText(0), s.columnText(1), s.columnText(2), s.columnText(3)};
    readField(s, 4, file_, kRunFields[1], k.status);
    out.push_back(std::move(k));
  }
  return out;
}

void ResultsDb::storeRun(const RunSpec& spec, const RunRecord& rec) {
  exec("BEGIN IMMEDIATE");
  try {
    // A retried run replaces everything stored under its key.
    for (const char* table : {"run_repetitions", "metrics", "planner_stats", "planner_timings", "paths", "run_options",
                              "run_car", "replans", "replan_figures"}) {
      Statement d(db_, std::string("DELETE FROM ") + table + " WHERE run_key = ?", file_);
      d.text(1, rec.key).run();
    }
    // The run's fields (kRunFields, the key first), its context, and when it finished.
    std::string marks;
    for (std::size_t n = 0; n < kRunFieldCount + std::size(kRunContextColumns); ++n) marks += "?,";
    Statement r(db_, "INSERT OR REPLACE INTO runs (" + runColumnList() + ") VALUES (" + marks + "?)", file_);
    int column = 0;
    forEachRunField(rec, [&](const RunField&, const auto& value) { bindField(r, ++column, value); });
    const int c = column;  // the context's columns follow, in kRunContextColumns' order
    r.text(c + 1, spec.base_key).text(c + 2, spec.wall->hash).text(c + 3, spec.planner->id);
    r.text(c + 4, spec.planner_version).text(c + 5, spec.code_sha256).text(c + 6, buildIdentity().describe());
    r.real(c + 7, spec.tool.tool_width).real(c + 8, spec.tool.clearance).integer(c + 9, static_cast<long long>(spec.seed));
    r.integer(c + 10, spec.repetitions).text(c + 11, utcNow()).run();
    if (!spec.vehicle.isDefault() || !spec.transit.isDefault()) {
      Statement v(db_,
                  "INSERT INTO run_options (run_key, vehicle, lift_s, lower_s, transit, transit_iterations) "
                  "VALUES (?,?,?,?,?,?)",
                  file_);
      v.text(1, rec.key).text(2, toString(spec.vehicle.kind)).real(3, spec.vehicle.lift_s).real(4, spec.vehicle.lower_s);
      v.text(5, spec.transit.planner).integer(6, spec.transit.iterations).run();
    }
    if (spec.vehicle.isCar()) {
      Statement car(db_, "INSERT INTO run_car (run_key, turn_radius, reverse) VALUES (?,?,?)", file_);
      car.text(1, rec.key).real(2, spec.vehicle.turn_radius).integer(3, spec.vehicle.reverse ? 1 : 0).run();
    }
    if (!rec.replans.empty()) {
      Statement rr(db_,
                   "INSERT INTO replans (run_key, position, fraction, repair, obstacles, requested, obstacles_json, status, "
                   "reason, valid, repair_ms, path, cut_waypoint) VALUES (?,?,?,?,?,?,?,?,?,?,?,?,?)",
                   file_);
      Statement rf(db_, "INSERT INTO replan_figures (run_key, position, name, value) VALUES (?,?,?,?)", file_);
      for (std::size_t i = 0; i < rec.replans.size(); ++i) {
        const ReplanRecord& p = rec.replans[i];
        const auto pos = static_cast<long long>(i);
        rr.text(1, rec.key).integer(2, pos).real(3, p.fraction).text(4, p.repair);
        rr.integer(5, static_cast<long long>(p.obstacles)).integer(6, static_cast<long long>(p.requested));
        rr.text(7, p.obstacles_json).text(8, p.status).text(9, p.reason).integer(10, p.valid ? 1 : 0).real(11, p.repair_ms);
        if (p.path.waypoints.empty()) rr.null(12);
        else rr.blob(12, encodePath(p.path));
        rr.integer(13, static_cast<long long>(p.cut_waypoint)).run();
        for (const auto& [name, value] : p.figures) rf.text(1, rec.key).integer(2, pos).text(3, name).real(4, value).run();
      }
    }
    Statement rp(db_, "INSERT INTO run_repetitions (run_key, repetition, plan_time_ms) VALUES (?,?,?)", file_);
    for (std::size_t i = 0; i < rec.plan_times_ms.size(); ++i)
      rp.text(1, rec.key).integer(2, static_cast<long long>(i)).real(3, rec.plan_times_ms[i]).run();
    Statement m(db_, "INSERT INTO metrics (run_key, position, name, value) VALUES (?,?,?,?)", file_);
    for (std::size_t i = 0; i < rec.metrics.size(); ++i) {
      // Every stored metric is one the registry describes (unit, direction), so reports can read it.
      const auto& [name, value] = rec.metrics[i];
      if (!findMetricSpec(name)) throw std::logic_error("metric '" + name + "' is not in the registry");
      m.text(1, rec.key).integer(2, static_cast<long long>(i)).text(3, name).real(4, value).run();
    }
    Statement st(db_, "INSERT INTO planner_stats (run_key, name, value) VALUES (?,?,?)", file_);
    for (const auto& [name, value] : rec.stats) st.text(1, rec.key).text(2, name).real(3, value).run();
    Statement tm(db_, "INSERT INTO planner_timings (run_key, name, ms) VALUES (?,?,?)", file_);
    for (const auto& [name, value] : rec.timings_ms) tm.text(1, rec.key).text(2, name).real(3, value).run();
    if (!rec.path.waypoints.empty()) {
      Statement p(db_, "INSERT INTO paths (run_key, encoding, waypoints, data) VALUES (?,?,?,?)", file_);
      p.text(1, rec.key).text(2, "zlib-f64le-1").integer(3, static_cast<long long>(rec.path.waypoints.size()));
      p.blob(4, rec.path_blob.empty() ? encodePath(rec.path) : rec.path_blob).run();
    }
    exec("COMMIT");
  } catch (...) {
    rollback();
    throw;
  }
}

void ResultsDb::finishExperiment(long long id, std::size_t executed, std::size_t skipped, std::size_t reused,
                                 const std::string& rerun_reasons) {
  Statement s(db_,
              "UPDATE experiments SET finished_at = ?, runs_executed = ?, runs_skipped = ?, runs_reused = ?, "
              "rerun_reasons = ? WHERE id = ?",
              file_);
  s.text(1, utcNow()).integer(2, static_cast<long long>(executed)).integer(3, static_cast<long long>(skipped));
  s.integer(4, static_cast<long long>(reused)).text(5, rerun_reasons).integer(6, id).run();
}

namespace {

/// The experiment's row (the latest when none is named) into `rs`; its id.
long long loadExperimentRow(sqlite3* db, const std::string& file, std::optional<long long> experiment, ResultSet& rs) {
  Statement s(db,
              experiment ? "SELECT id, name, config_hash, baseline FROM experiments WHERE id = ?"
                         : "SELECT id, name, config_hash, baseline FROM experiments ORDER BY id DESC LIMIT 1",
              file);
  if (experiment) s.integer(1, *experiment);
  if (!s.step()) throw InputError(file, "experiments", experiment ? "has no experiment " + std::to_string(*experiment) : "is empty");
  rs.experiment = s.columnText(1);
  rs.config_hash = s.columnText(2);
  rs.baseline = s.columnText(3);
  return s.columnInt(0);
}

}  // namespace

ResultSet ResultsDb::load(std::optional<long long> experiment) {
  ResultSet rs;
  const long long id = loadExperimentRow(db_, file_, experiment, rs);
  std::map<std::string, std::string> label_of, params_of;
  {
    Statement s(db_,
                "SELECT e.config_id, e.label, p.params FROM experiment_planners e JOIN planner_configs p ON p.id = e.config_id "
                "WHERE e.experiment_id = ? ORDER BY e.position",
                file_);
    s.integer(1, id);
    while (s.step()) {
      label_of[s.columnText(0)] = s.columnText(1);
      params_of[s.columnText(0)] = s.columnText(2);
      rs.planners.push_back(s.columnText(1));
    }
  }
  {
    // Metric order: as the engine lists them (position), then the run figures.
    Statement s(db_,
                "SELECT name FROM metrics m JOIN experiment_runs e ON e.run_key = m.run_key WHERE e.experiment_id = ? "
                "GROUP BY name ORDER BY MIN(position), name",
                file_);
    s.integer(1, id);
    while (s.step()) rs.metric_order.push_back(s.columnText(0));
    rs.metric_order.push_back("plan_time_ms");
    rs.metric_order.push_back("peak_memory_bytes");
  }
  std::map<std::string, std::size_t> index;
  {
    // The context (columns 0 .. 7), the options (8 .. 14), then the run's fields (15 ..).
    Statement s(db_,
                "SELECT r.config_id, w.dataset, r.wall_hash, r.tool_width, r.clearance, r.seed, ws.name, r.planner_version, " +
                    std::string(kOptionColumns) + ", " + runFieldSelect("r") + " FROM runs r "
                "JOIN experiment_runs e ON e.run_key = r.key AND e.experiment_id = ?1 "
                "JOIN experiment_walls w ON w.wall_hash = r.wall_hash AND w.experiment_id = ?1 "
                "JOIN walls ws ON ws.hash = r.wall_hash" + std::string(kOptionJoins) + "ORDER BY r.key",
                file_);
    s.integer(1, id);
    while (s.step()) {
      ResultRow row;
      row.planner = label_of[s.columnText(0)];
      row.params = params_of[s.columnText(0)];
      row.dataset = s.columnText(1);
      row.wall = s.columnText(2);
      char pairing[160];
      std::snprintf(pairing, sizeof pairing, "%s/%.17g/%.17g/%lld", row.wall.c_str(), s.columnReal(3), s.columnReal(4),
                    s.columnInt(5));
      row.pairing = pairing;
      row.config = row.planner;
      row.wall_name = s.columnText(6);
      row.planner_version = s.columnText(7);
      row.tool = ToolParams{s.columnReal(3), s.columnReal(4)};
      storedOptions(s, 8, row.vehicle, row.transit);
      int i = 15;
      forEachRunField(static_cast<RunFields&>(row), [&](const RunField& f, auto& value) { readField(s, i++, file_, f, value); });
      // The measured fields the metric registry lists are the tables' metrics too.
      row.metrics["plan_time_ms"] = row.plan_time_ms;
      if (std::isfinite(row.peak_memory_bytes)) row.metrics["peak_memory_bytes"] = row.peak_memory_bytes;
      index[row.key] = rs.runs.size();
      rs.runs.push_back(std::move(row));
    }
  }
  // Each tool configuration is its own group: with several, every column is "label @ tool".
  std::set<std::pair<double, double>> tools;
  for (const ResultRow& r : rs.runs) tools.insert({r.tool.tool_width, r.tool.clearance});
  if (tools.size() > 1) {
    auto suffix = [](double w, double c) { return " @ " + toolLabel(ToolParams{w, c}); };
    std::vector<std::string> columns;
    for (const std::string& label : rs.planners)
      for (const auto& [w, c] : tools) columns.push_back(label + suffix(w, c));
    rs.planners = columns;
    for (ResultRow& r : rs.runs) r.planner = r.config + suffix(r.tool.tool_width, r.tool.clearance);
  }
  // So is each transit planner: with several, every column also gets "@ transit=NAME" (in the
  // registry's order), and runs differing only in it pair up on the same walls.
  std::set<std::string> used;
  for (const ResultRow& r : rs.runs) used.insert(r.transit.planner);
  if (used.size() > 1) {
    std::vector<std::string> columns;
    for (const std::string& label : rs.planners)
      for (const TransitPlannerInfo& t : transitPlanners())
        if (used.count(t.name)) columns.push_back(label + " @ transit=" + t.name);
    rs.planners = columns;
    for (ResultRow& r : rs.runs) r.planner += " @ transit=" + r.transit.planner;
  }
  // Rows (run key, name, value) of the experiment's runs into a map of each run. NULL is how
  // infinities are stored (min_clearance with no obstacles): kept out of statistics.
  auto named = [&](const std::string& sql, std::map<std::string, double> ResultRow::*into) {
    Statement s(db_, sql, file_);
    s.integer(1, id);
    while (s.step()) {
      const auto it = index.find(s.columnText(0));
      if (it != index.end() && !s.columnNull(2)) (rs.runs[it->second].*into)[s.columnText(1)] = s.columnReal(2);
    }
  };
  named("SELECT m.run_key, m.name, m.value FROM metrics m JOIN experiment_runs e ON e.run_key = m.run_key "
        "WHERE e.experiment_id = ?1",
        &ResultRow::metrics);
  if (used.size() > 1 || (used.size() == 1 && *used.begin() != TransitSpec{}.planner))
    named("SELECT t.run_key, t.name, t.value FROM planner_stats t JOIN experiment_runs e ON e.run_key = t.run_key "
          "WHERE e.experiment_id = ?1 AND t.name LIKE 'transit\\_%' ESCAPE '\\' "
          "UNION ALL SELECT t.run_key, 'transit_ms', t.ms FROM planner_timings t JOIN experiment_runs e "
          "ON e.run_key = t.run_key WHERE e.experiment_id = ?1 AND t.name = 'transit'",
          &ResultRow::transit_figures);
  {
    Statement s(db_,
                "SELECT p.run_key, p.position, p.fraction, p.repair, p.obstacles, p.requested, p.status, p.valid, p.repair_ms "
                "FROM replans p JOIN experiment_runs e ON e.run_key = p.run_key WHERE e.experiment_id = ?1 "
                "ORDER BY p.run_key, p.position",
                file_);
    s.integer(1, id);
    while (s.step()) {
      const auto it = index.find(s.columnText(0));
      if (it == index.end()) continue;
      ReplanRow p;
      p.fraction = s.columnReal(2);
      p.repair = s.columnText(3);
      p.obstacles = static_cast<std::size_t>(s.columnInt(4));
      p.requested = static_cast<std::size_t>(s.columnInt(5));
      p.status = s.columnText(6);
      p.valid = s.columnInt(7) != 0;
      p.repair_ms = s.columnNull(8) ? NAN : s.columnReal(8);
      rs.runs[it->second].replans.push_back(std::move(p));
    }
    Statement f(db_,
                "SELECT f.run_key, f.position, f.name, f.value FROM replan_figures f JOIN experiment_runs e "
                "ON e.run_key = f.run_key WHERE e.experiment_id = ?1",
                file_);
    f.integer(1, id);
    while (f.step()) {
      const auto it = index.find(f.columnText(0));
      if (it == index.end() || f.columnNull(3)) continue;
      auto& replans = rs.runs[it->second].replans;
      const auto pos = static_cast<std::size_t>(f.columnInt(1));
      if (pos < replans.size()) replans[pos].figures[f.columnText(2)] = f.columnReal(3);
    }
  }
  return rs;
}

std::vector<ResultsDb::ExperimentEntry> ResultsDb::experiments() {
  std::vector<ExperimentEntry> out;
  Statement s(db_,
              "SELECT e.id, e.name, (SELECT COUNT(*) FROM experiment_runs r WHERE r.experiment_id = e.id) "
              "FROM experiments e ORDER BY e.id",
              file_);
  while (s.step()) out.push_back({s.columnInt(0), s.columnText(1), s.columnInt(2)});
  return out;
}

std::vector<ResultsDb::RunSummary> ResultsDb::runSummaries(long long experiment) {
  {
    Statement s(db_, "SELECT 1 FROM experiments WHERE id = ?", file_);
    s.integer(1, experiment);
    if (!s.step()) throw InputError(file_, "experiments", "has no experiment " + std::to_string(experiment));
  }
  std::map<std::string, std::string> label_of;
  {
    Statement s(db_, "SELECT config_id, label FROM experiment_planners WHERE experiment_id = ? ORDER BY position", file_);
    s.integer(1, experiment);
    while (s.step()) label_of.emplace(s.columnText(0), s.columnText(1));
  }
  const std::set<std::string> columns = runColumns();
  auto column = [&](const char* name) { return columns.count(name) ? std::string("r.") + name : std::string("NULL"); };
  Statement s(db_,
              "SELECT e.run_key, r.config_id, w.dataset, r.wall_hash, ws.name, r.status, r.tool_width, r.clearance, " +
                  column("plan_time_ms") + ", " + column("peak_memory_bytes") +
                  ", COALESCE(o.transit, '') FROM experiment_runs e JOIN runs r ON r.key = e.run_key "
                  "JOIN experiment_walls w ON w.experiment_id = ?1 AND w.wall_hash = r.wall_hash "
                  "JOIN walls ws ON ws.hash = r.wall_hash LEFT JOIN run_options o ON o.run_key = e.run_key "
                  "WHERE e.experiment_id = ?1 ORDER BY e.run_key",
              file_);
  s.integer(1, experiment);
  std::vector<RunSummary> out;
  std::vector<std::string> transits;
  std::set<std::string> used;
  while (s.step()) {
    RunSummary r;
    r.key = s.columnText(0);
    r.planner = label_of[s.columnText(1)];
    r.dataset = s.columnText(2);
    r.wall = s.columnText(3);
    r.wall_name = s.columnText(4);
    readField(s, 5, file_, kRunFields[1], r.status);
    r.tool = ToolParams{s.columnReal(6), s.columnReal(7)};
    r.plan_time_ms = s.columnReal(8);
    r.peak_memory_bytes = s.columnReal(9);
    transits.push_back(s.columnText(10).empty() ? TransitSpec{}.planner : s.columnText(10));
    used.insert(transits.back());
    out.push_back(std::move(r));
  }
  // Runs that differ only in their transit planner are different configurations (as in load()).
  if (used.size() > 1)
    for (std::size_t i = 0; i < out.size(); ++i) out[i].planner += " @ transit=" + transits[i];
  return out;
}

std::vector<std::string> ResultsDb::metricNames(long long experiment) {
  std::vector<std::string> names;
  // The metrics a run has are the engine's (and the exact judge's, the same for every run of an
  // experiment): one build stores the same names for every scored run. So the names of one scored
  // run per build are all of them, read without scanning every metric of 10^5 runs.
  Statement s(db_,
              "SELECT name FROM metrics WHERE run_key IN (SELECT MIN(r.key) FROM experiment_runs e JOIN runs r ON r.key = e.run_key "
              "WHERE e.experiment_id = ?1 AND EXISTS (SELECT 1 FROM metrics x WHERE x.run_key = r.key) GROUP BY r.build) "
              "GROUP BY name ORDER BY MIN(position), name",
              file_);
  s.integer(1, experiment);
  while (s.step()) names.push_back(s.columnText(0));
  names.push_back("plan_time_ms");
  names.push_back("peak_memory_bytes");
  return names;
}

std::vector<double> ResultsDb::metricColumn(long long experiment, const std::string& metric) {
  std::vector<double> out;
  Statement s(db_,
              "SELECT m.value FROM experiment_runs e LEFT JOIN metrics m ON m.run_key = e.run_key AND m.name = ?2 "
              "WHERE e.experiment_id = ?1 ORDER BY e.run_key",
              file_);
  s.integer(1, experiment).text(2, metric);
  while (s.step()) out.push_back(s.columnReal(0));
  return out;
}

std::map<std::string, std::map<std::string, double>> ResultsDb::metricsOf(const std::vector<std::string>& run_keys) {
  std::map<std::string, std::map<std::string, double>> out;
  const std::set<std::string> columns = runColumns();
  const std::string peak = columns.count("peak_memory_bytes") ? "peak_memory_bytes" : "NULL";
  Statement m(db_, "SELECT name, value FROM metrics WHERE run_key = ?", file_);
  Statement r(db_, "SELECT plan_time_ms, " + peak + " FROM runs WHERE key = ?", file_);
  for (const std::string& key : run_keys) {
    auto& into = out[key];
    m.text(1, key);
    while (m.step())
      if (!m.columnNull(1)) into[m.columnText(0)] = m.columnReal(1);
    m.reset();
    r.text(1, key);
    if (r.step()) {
      into["plan_time_ms"] = r.columnReal(0);
      if (!r.columnNull(1)) into["peak_memory_bytes"] = r.columnReal(1);
    }
    r.reset();
  }
  return out;
}

ExperimentRecord ResultsDb::record(std::optional<long long> experiment) {
  ExperimentRecord r;
  {
    Statement s(db_,
                std::string("SELECT id, name, COALESCE(config_path, ''), config_text, config_hash, baseline, command_line, "
                            "git_revision, git_diff_sha256, compiler, build_type, build_flags, host, cpu, cores, os, "
                            "memory_bytes, workers, started_at, COALESCE(finished_at, ''), runs_total, runs_executed, "
                            "runs_skipped, runs_reused, COALESCE(rerun_reasons, '') FROM experiments ") +
                    (experiment ? "WHERE id = ?" : "ORDER BY id DESC LIMIT 1"),
                file_);
    if (experiment) s.integer(1, *experiment);
    if (!s.step())
      throw InputError(file_, "experiments", experiment ? "has no experiment " + std::to_string(*experiment) : "is empty");
    r.id = s.columnInt(0);
    r.name = s.columnText(1);
    r.config_path = s.columnText(2);
    r.config_text = s.columnText(3);
    r.config_hash = s.columnText(4);
    r.baseline = s.columnText(5);
    r.motion = configMotion(r.config_text, file_ + ": experiments.config_text").describe();
    auto count = [&](int column) { return s.columnNull(column) ? std::string("-") : std::to_string(s.columnInt(column)); };
    const std::string revision = s.columnText(7), diff = s.columnText(8);
    r.facts = {{"command line", s.columnText(6)},
               {"git revision", revision + (diff.empty() ? "" : " with uncommitted changes (diff sha256 " + diff + ")")},
               {"compiler", s.columnText(9)},
               {"build type", s.columnText(10)},
               {"build flags", s.columnText(11)},
               {"host", s.columnText(12)},
               {"CPU", s.columnText(13)},
               {"cores", std::to_string(s.columnInt(14))},
               {"OS", s.columnText(15)},
               {"memory", s.columnNull(16) ? "-" : gibibytes(s.columnReal(16))},
               {"worker processes", std::to_string(s.columnInt(17))},
               {"started (UTC)", s.columnText(18)},
               {"finished (UTC)", s.columnText(19).empty() ? "not finished" : s.columnText(19)},
               {"runs", count(20) + " (" + count(21) + " executed, " + count(22) + " already stored, " + count(23) +
                            " reused from other builds)"},
               {"run again because", s.columnText(24).empty() ? "-" : s.columnText(24)}};
  }
  {
    // A shard, or a merge of shards: say so next to the run counts.
    Statement sh(db_, "SELECT shard_index, shard_count, config_runs FROM experiment_shard WHERE experiment_id = ?", file_);
    sh.integer(1, r.id);
    if (sh.step())
      r.facts.push_back({"shard", std::to_string(sh.columnInt(0)) + "/" + std::to_string(sh.columnInt(1)) + " (" +
                                      std::to_string(sh.columnInt(2)) + " runs in the whole config)"});
    Statement m(db_,
                "SELECT COUNT(DISTINCT shard_index), MAX(shard_count), COUNT(DISTINCT host), SUM(runs) FROM merged_shards "
                "WHERE experiment_id = ?",
                file_);
    m.integer(1, r.id);
    if (m.step() && m.columnInt(0) > 0)
      r.facts.push_back({"merged from", std::to_string(m.columnInt(0)) + " shards of " + std::to_string(m.columnInt(1)) +
                                            " run on " + std::to_string(m.columnInt(2)) + " host(s) (table merged_shards)"});
  }
  {
    Statement s(db_,
                "SELECT label, source, walls, sha256 FROM experiment_datasets WHERE experiment_id = ? ORDER BY position",
                file_);
    s.integer(1, r.id);
    while (s.step()) r.datasets.push_back({s.columnText(0), s.columnText(1), s.columnText(3), s.columnInt(2)});
  }
  {
    Statement s(db_,
                "SELECT e.label, p.planner, p.params FROM experiment_planners e JOIN planner_configs p ON p.id = e.config_id "
                "WHERE e.experiment_id = ? ORDER BY e.position",
                file_);
    s.integer(1, r.id);
    while (s.step()) r.planners.push_back({s.columnText(0), s.columnText(1), s.columnText(2)});
  }
  {
    Statement s(db_,
                "SELECT w.hash, w.name, w.content FROM walls w JOIN experiment_walls e ON e.wall_hash = w.hash "
                "WHERE e.experiment_id = ? ORDER BY w.hash",
                file_);
    s.integer(1, r.id);
    while (s.step()) {
      const Wall wall = parseWallJson(s.columnText(2), file_ + " (wall " + s.columnText(1) + ")");
      r.walls.push_back({s.columnText(0), s.columnText(1), wall.obstacles.size(), std::fabs(signedArea(wall.boundary))});
    }
  }
  return r;
}

std::optional<Path> ResultsDb::path(const std::string& run_key) {
  Statement s(db_, "SELECT data FROM paths WHERE run_key = ?", file_);
  s.text(1, run_key);
  if (!s.step()) return std::nullopt;
  try {
    return decodePath(s.columnBlob(0));
  } catch (const InputError& e) {
    throw InputError(file_, "paths[" + run_key + "]", e.problem());
  }
}

ResultsDb::StoredRun ResultsDb::storedRun(const std::string& key_prefix) {
  if (key_prefix.size() < 6 || key_prefix.find_first_not_of("0123456789abcdef") != std::string::npos)
    throw InputError("--run", "run", "must be at least 6 lowercase hex digits of a run key");
  Statement s(db_,
              "SELECT r.key, w.content, w.name, p.planner, p.params, r.tool_width, r.clearance, r.status, r.reason, " +
                  std::string(kOptionColumns) + ", " +
                  (runColumns().count("stderr_tail") ? "r.stderr_tail" : "''") +
                  " FROM runs r JOIN walls w ON w.hash = r.wall_hash JOIN planner_configs p ON p.id = r.config_id" +
                  std::string(kOptionJoins) +
              "WHERE r.key >= ?1 AND r.key < ?1 || 'g' ORDER BY r.key LIMIT 2",
              file_);
  s.text(1, key_prefix);
  if (!s.step()) throw InputError(file_, "runs", "no run key starts with " + key_prefix);
  StoredRun run;
  run.key = s.columnText(0);
  run.wall = parseWallJson(s.columnText(1), file_ + " (wall " + s.columnText(2) + ")");
  const std::string params = paramsLine(s.columnText(4));
  run.planner = s.columnText(3) + (params.empty() ? "" : " (" + params + ")");
  run.planner_name = s.columnText(3);
  run.params_json = s.columnText(4);
  run.tool = ToolParams{s.columnReal(5), s.columnReal(6)};
  run.status = s.columnText(7);
  run.reason = s.columnText(8);
  TransitSpec transit;
  storedOptions(s, 9, run.vehicle, transit);
  run.stderr_tail = s.columnText(16);  // after the 7 option columns
  if (s.step()) throw InputError(file_, "runs", "several run keys start with " + key_prefix + ": give more digits");
  if (std::optional<Path> p = path(run.key)) run.path = std::move(*p);
  return run;
}

ResultsDb::StoredRun ResultsDb::storedReplan(const std::string& key_prefix, std::size_t position) {
  StoredRun run = storedRun(key_prefix);
  Statement s(db_,
              "SELECT fraction, repair, obstacles_json, status, reason, path, cut_waypoint FROM replans WHERE run_key = ? AND position = ?",
              file_);
  s.text(1, run.key).integer(2, static_cast<long long>(position));
  if (!s.step()) {
    Statement n(db_, "SELECT COUNT(*) FROM replans WHERE run_key = ?", file_);
    n.text(1, run.key);
    n.step();
    const long long count = n.columnInt(0);
    throw InputError("--replan", "replan",
                     "run " + run.key.substr(0, 12) + " has " +
                         (count ? std::to_string(count) + " repairs (numbers 0 to " + std::to_string(count - 1) + ")"
                                : std::string("no repairs (its experiment had no replanning: section)")) +
                         ", not number " + std::to_string(position));
  }
  char what[96];
  std::snprintf(what, sizeof what, ", obstacles at %g, repaired by %s", s.columnReal(0), s.columnText(1).c_str());
  run.planner += what;
  for (Obstacle& o : parseObstaclesJson(s.columnText(2), file_ + " (replans of " + run.key.substr(0, 12) + ")"))
    run.wall.obstacles.push_back(std::move(o));
  run.status = s.columnText(3);
  run.reason = s.columnText(4);
  run.path = s.columnNull(5) ? Path{} : decodePath(s.columnBlob(5));
  run.first_judged_segment = static_cast<std::size_t>(s.columnInt(6));
  return run;
}

}  // namespace coverbench
