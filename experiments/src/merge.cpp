// `coverbench merge`: shard databases into one, on run key, in one transaction. docs/scaling.md.
#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include "coverbench/hash.hpp"
#include "coverbench/results_db.hpp"
#include "coverbench/shards.hpp"
#include "run_columns.hpp"
#include "sqlite_statement.hpp"

namespace coverbench {
namespace {

/// A read-only connection to a shard file, closed on scope exit.
struct ReadConnection {
  explicit ReadConnection(const std::string& path) : file(path) {
    if (sqlite3_open_v2(path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
      sqlite3_close(db);
      throw InputError(path, "(database)", "cannot be opened");
    }
    sqlite3_busy_timeout(db, 10000);
  }
  ~ReadConnection() { sqlite3_close(db); }
  ReadConnection(const ReadConnection&) = delete;
  ReadConnection& operator=(const ReadConnection&) = delete;
  sqlite3* db = nullptr;
  std::string file;
};

/// One shard file's latest experiment, as the merge sees it.
struct ShardFile {
  std::string path;
  long long experiment = 0;  ///< its latest experiment's id in that file
  Shard shard;
  std::size_t config_runs = 0;
  std::string config_hash, build, datasets, host, cpu;  ///< build: revision, diff, compiler, type, flags
  long long workers = 0, executed = 0;
  std::string started_at, finished_at;   ///< of the file's first and latest experiment
  std::vector<std::string> expected;     ///< the shard's run keys (its latest experiment's), sorted
  std::set<std::string> present;         ///< those stored in the file
  std::string rerun_reasons;
};

std::string firstKeys(const std::vector<std::string>& keys) {
  std::string out;
  for (std::size_t i = 0; i < keys.size() && i < 3; ++i) out += (i ? ", " : "") + keys[i].substr(0, 12);
  return out + (keys.size() > 3 ? ", ..." : "");
}

/// Whether a CoverBench results database holds a shard's experiments (read only).
bool isShardDatabase(const std::string& path) {
  ResultsDb check(path, ResultsDb::Mode::ReadOnly);  // a CoverBench database of this schema, or an InputError
  const ReadConnection connection(path);
  Statement t(connection.db, "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = 'experiment_shard'", path);
  if (!t.step()) return false;
  Statement n(connection.db, "SELECT 1 FROM experiment_shard LIMIT 1", path);
  return n.step();
}

/// Reads what the merge needs from one shard file (opened read-only; never written).
ShardFile readShard(const std::string& path) {
  ResultsDb check(path, ResultsDb::Mode::ReadOnly);  // a CoverBench database of this schema, or an InputError
  const ReadConnection connection(path);
  sqlite3* db = connection.db;
  ShardFile f;
  f.path = path;
  bool has_table = false;
  {
    Statement t(db, "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = 'experiment_shard'", path);
    has_table = t.step();
  }
  if (!has_table) throw InputError(path, "(database)", "is not a shard database (written by `coverbench run` without --shard)");
  {
    Statement s(db,
                "SELECT COUNT(*) FROM experiments e LEFT JOIN experiment_shard s ON s.experiment_id = e.id "
                "WHERE s.experiment_id IS NULL",
                path);
    s.step();
    if (s.columnInt(0) > 0)
      throw InputError(path, "experiments", "holds an experiment that is not a shard (run without --shard): not a shard database");
  }
  {
    Statement s(db,
                "SELECT e.id, s.shard_index, s.shard_count, s.config_runs, e.config_hash, e.git_revision || ' ' || "
                "e.git_diff_sha256 || ' ' || e.compiler || ' ' || e.build_type || ' ' || e.build_flags, e.host, e.workers, "
                "COALESCE(e.finished_at, ''), COALESCE(e.rerun_reasons, ''), e.cpu FROM experiments e "
                "JOIN experiment_shard s ON s.experiment_id = e.id ORDER BY e.id DESC LIMIT 1",
                path);
    if (!s.step()) throw InputError(path, "experiments", "is empty: the shard never started");
    f.experiment = s.columnInt(0);
    f.shard = Shard{static_cast<unsigned>(s.columnInt(1)), static_cast<unsigned>(s.columnInt(2))};
    f.config_runs = static_cast<std::size_t>(s.columnInt(3));
    f.config_hash = s.columnText(4);
    f.build = s.columnText(5);
    f.host = s.columnText(6);
    f.workers = s.columnInt(7);
    f.finished_at = s.columnText(8);
    f.rerun_reasons = s.columnText(9);
    f.cpu = s.columnText(10);
  }
  {
    // A shard file holds one shard: every experiment in it (a start and its resumptions) the same.
    Statement s(db, "SELECT COUNT(DISTINCT shard_index || '/' || shard_count) FROM experiment_shard", path);
    s.step();
    if (s.columnInt(0) != 1) throw InputError(path, "experiment_shard", "holds experiments of several shards; give each shard its own file");
  }
  {
    Statement s(db, "SELECT MIN(started_at), SUM(COALESCE(runs_executed, 0)) FROM experiments", path);
    s.step();
    f.started_at = s.columnText(0);
    f.executed = s.columnInt(1);
  }
  {
    Statement s(db, "SELECT label || ' ' || sha256 FROM experiment_datasets WHERE experiment_id = ? ORDER BY position", path);
    s.integer(1, f.experiment);
    while (s.step()) f.datasets += s.columnText(0) + "\n";
  }
  {
    Statement s(db,
                "SELECT e.run_key, r.key IS NOT NULL FROM experiment_runs e LEFT JOIN runs r ON r.key = e.run_key "
                "WHERE e.experiment_id = ? ORDER BY e.run_key",
                path);
    s.integer(1, f.experiment);
    while (s.step()) {
      f.expected.push_back(s.columnText(0));
      if (s.columnInt(1)) f.present.insert(s.columnText(0));
    }
  }
  return f;
}

/// Everything a run's result is (its fields that are not measured, kRunFields; its metrics,
/// statistics and path): for telling identical duplicates from conflicting ones.
std::string runContent(sqlite3* db, const std::string& key, const std::string& file) {
  const std::string fields = runFieldExpressions(
      tableColumns(db, "runs", file), "r", [](const RunField& f) { return !f.measured && std::string_view(f.name) != "key"; },
      "quote(%)", " || '|' || ");
  std::string out;
  for (const std::string& sql : {"SELECT " + fields + " FROM runs r WHERE key = ?",
                          std::string("SELECT name || '=' || quote(value) FROM metrics WHERE run_key = ? ORDER BY name"),
                          std::string("SELECT name || '=' || quote(value) FROM planner_stats WHERE run_key = ? ORDER BY name"),
                          std::string("SELECT hex(data) FROM paths WHERE run_key = ?")}) {
    Statement s(db, sql, file);
    s.text(1, key);
    while (s.step()) out += s.columnText(0) + "\n";
  }
  return out;
}

/// Inserts every row `select` yields into `dst` with `insert` ("INSERT INTO t VALUES", the
/// placeholders added here), values as they are; rows whose first column is not in `only` are
/// skipped (when given).
void copyRows(Statement& select, sqlite3* dst, const std::string& insert, const std::string& dst_file,
              const std::set<std::string>* only) {
  std::unique_ptr<Statement> ins;
  while (select.step()) {
    if (only && !only->count(select.columnText(0))) continue;
    if (!ins) {
      std::string sql = insert + " (";
      for (int c = 0; c < select.columnCount(); ++c) sql += c ? ",?" : "?";
      ins = std::make_unique<Statement>(dst, sql + ")", dst_file);
    }
    for (int c = 0; c < select.columnCount(); ++c) ins->value(c + 1, select.columnValue(c));
    ins->run();
  }
}
/// The same for a query of a shard's rows of one experiment (bound as ?1).
void copyRows(const ReadConnection& src, const std::string& select, long long experiment, sqlite3* dst,
              const std::string& insert, const std::string& dst_file, const std::set<std::string>* only) {
  Statement sel(src.db, select, src.file);
  sel.integer(1, experiment);
  copyRows(sel, dst, insert, dst_file, only);
}

std::string joinDistinct(const std::vector<std::string>& items, const std::string& sep) {
  std::vector<std::string> v = items;
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  std::string out;
  for (const std::string& s : v) out += (out.empty() ? "" : sep) + s;
  return out;
}

/// Per shard file (index, absolute path): the SHA-256 of its run keys. A merge is the same merge
/// when these are.
using Fingerprint = std::map<std::pair<unsigned, std::string>, std::string>;
Fingerprint fingerprints(const std::vector<ShardFile>& files) {
  Fingerprint out;
  for (const ShardFile& f : files) {
    std::string keys;
    for (const std::string& k : f.expected) keys += k + "\n";
    out[{f.shard.index, std::filesystem::absolute(f.path).string()}] = sha256Hex(keys);
  }
  return out;
}

/// The output's latest experiment when it is a merge of exactly these shard files' runs (read
/// only: an idempotent merge does not touch the file at all).
std::optional<long long> alreadyMerged(const std::string& out, const Fingerprint& fingerprint) {
  std::error_code ec;
  if (!std::filesystem::exists(out, ec)) return std::nullopt;
  ResultsDb check(out, ResultsDb::Mode::ReadOnly);  // CoverBench's, of this schema
  const ReadConnection c(out);
  Statement t(c.db, "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = 'merged_shards'", out);
  if (!t.step()) return std::nullopt;
  Statement s(c.db,
              "SELECT e.id, m.shard_index, m.source, m.runs_sha256 FROM experiments e JOIN merged_shards m "
              "ON m.experiment_id = e.id WHERE e.id = (SELECT MAX(id) FROM experiments)",
              out);
  Fingerprint latest;
  long long id = 0;
  while (s.step()) {
    id = s.columnInt(0);
    latest[{static_cast<unsigned>(s.columnInt(1)), s.columnText(2)}] = s.columnText(3);
  }
  if (latest.empty() || latest != fingerprint) return std::nullopt;
  return id;
}

}  // namespace

/// The results database's connection and transaction helpers, for the merge's row copying.
struct ResultsDbAccess {
  static sqlite3* connection(ResultsDb& d) { return d.db_; }
  static void exec(ResultsDb& d, const std::string& sql) { d.exec(sql); }
  static void rollback(ResultsDb& d) noexcept { d.rollback(); }
};

namespace {
MergeSummary writeMerged(const MergeOptions& options, const std::vector<ShardFile>& files,
                         const std::set<std::string>& expected_all, const Fingerprint& fingerprint, MergeSummary summary);
}  // namespace

MergeSummary mergeShards(const MergeOptions& options) {
  namespace fs = std::filesystem;
  if (options.shards.empty()) throw InputError("merge", "shards", "give at least one shard database");
  MergeSummary summary;

  // Read and check every shard before anything is written.
  std::vector<ShardFile> files;
  std::set<std::string> seen_paths;
  std::error_code ec;
  const fs::path out_path = fs::weakly_canonical(options.out, ec);
  const bool out_exists = fs::exists(options.out, ec);
  for (const std::string& path : options.shards) {
    const std::string canonical = fs::weakly_canonical(path, ec).string();
    // The same file by another name too (a hard link, a bind mount): inputs are never written.
    if (canonical == out_path.string() || (out_exists && fs::exists(path, ec) && fs::equivalent(path, options.out, ec)))
      throw InputError(path, "shards", "is the output database itself (" + options.out + "): a merge never writes its inputs");
    if (!seen_paths.insert(canonical).second) {
      summary.notes.push_back(path + " given twice: read once");
      continue;
    }
    files.push_back(readShard(path));
  }
  if (out_exists && fs::file_size(options.out, ec) > 0 && isShardDatabase(options.out))
    throw InputError(options.out, "output",
                     "is a shard database (written by `coverbench run --shard`): merging into it would make it "
                     "unmergeable; name a new file or a merged results database");
  std::sort(files.begin(), files.end(), [](const ShardFile& a, const ShardFile& b) {
    return a.shard.index != b.shard.index ? a.shard.index < b.shard.index : a.path < b.path;
  });
  const ShardFile& first = files.front();
  for (const ShardFile& f : files) {
    auto differs = [&](const std::string& what, const std::string& mine, const std::string& theirs) {
      if (mine != theirs)
        throw InputError(f.path, what,
                         "differs from " + first.path + "'s (" + theirs.substr(0, 80) + " here: " + mine.substr(0, 80) +
                             "): shards of different experiments or builds cannot be merged");
    };
    differs("config_hash", f.config_hash, first.config_hash);
    differs("build", f.build, first.build);
    differs("shard count", std::to_string(f.shard.count), std::to_string(first.shard.count));
    differs("config runs", std::to_string(f.config_runs), std::to_string(first.config_runs));
    if (f.datasets != first.datasets)
      throw InputError(f.path, "experiment_datasets",
                       "the walls differ from " + first.path + "'s (a folder dataset read differently on two machines?)");
  }
  const unsigned n = first.shard.count;
  summary.shard_count = n;
  summary.shard_files = files.size();
  summary.runs = first.config_runs;

  // Per shard index: the files that ran it. Missing shards and missing runs are refused.
  std::map<unsigned, std::vector<const ShardFile*>> by_index;
  for (const ShardFile& f : files) by_index[f.shard.index].push_back(&f);
  std::vector<std::string> problems;
  std::vector<unsigned> absent;
  for (unsigned i = 0; i < n; ++i)
    if (!by_index.count(i)) absent.push_back(i);
  if (!absent.empty()) {
    std::string list;
    for (std::size_t k = 0; k < absent.size() && k < 10; ++k) list += (k ? ", " : "") + std::to_string(absent[k]);
    problems.push_back(std::to_string(absent.size()) + " of " + std::to_string(n) + " shards not given (" + list +
                       (absent.size() > 10 ? ", ..." : "") + ")");
  }
  std::set<std::string> expected_all;
  std::size_t expected_count = 0;
  for (const auto& [index, group] : by_index) {
    std::set<std::string> present;
    for (const ShardFile* f : group) {
      if (f->expected != group.front()->expected)
        throw InputError(f->path, "experiment_runs",
                         "shard " + toString(f->shard) + " lists other runs than " + group.front()->path +
                             " (another config or build)");
      present.insert(f->present.begin(), f->present.end());
    }
    if (group.size() > 1) {
      std::string paths;
      for (const ShardFile* f : group) paths += (paths.empty() ? "" : ", ") + f->path;
      summary.notes.push_back("shard " + toString(group.front()->shard) + " given in " + std::to_string(group.size()) +
                              " files (" + paths + "): runs stored in several are compared and kept once");
    }
    std::vector<std::string> missing;
    for (const std::string& key : group.front()->expected)
      if (!present.count(key)) missing.push_back(key);
    if (!missing.empty())
      problems.push_back("shard " + toString(group.front()->shard) + " (" + group.front()->path + ") lacks " +
                         std::to_string(missing.size()) + " of its " + std::to_string(group.front()->expected.size()) +
                         " runs (" + firstKeys(missing) + "): resume it with `coverbench run CONFIG --shard " +
                         toString(group.front()->shard) + "`");
    for (const std::string& key : group.front()->expected)
      if (!expected_all.insert(key).second)
        throw InputError(group.front()->path, "experiment_runs",
                         "run " + key.substr(0, 12) + " belongs to two shards: the shards were not made by one partition");
    expected_count += group.front()->expected.size();
  }
  if (!problems.empty()) {
    std::string all;
    for (const std::string& p : problems) all += (all.empty() ? "" : "; ") + p;
    throw InputError(options.out, "shards", "incomplete, nothing written: " + all);
  }
  if (expected_count != first.config_runs)
    throw InputError(first.path, "experiment_shard",
                     "the shards list " + std::to_string(expected_count) + " runs but the config has " +
                         std::to_string(first.config_runs) + ": the shards were not made by one partition");

  // Write: everything in one transaction on the output; an output this merge created is removed
  // again if the merge fails.
  if (fs::path parent = fs::path(options.out).parent_path(); !parent.empty()) {
    fs::create_directories(parent, ec);
    if (ec) throw InputError(options.out, "output", "its folder cannot be created: " + ec.message());
  }
  std::vector<std::string> hosts;
  for (const ShardFile& f : files) hosts.push_back(f.host);
  summary.hosts = joinDistinct(hosts, ", ");
  const Fingerprint fingerprint = fingerprints(files);
  if (const std::optional<long long> id = alreadyMerged(options.out, fingerprint)) {
    summary.unchanged = true;
    summary.already_stored = first.config_runs;
    summary.experiment_id = *id;
    return summary;
  }
  const bool existed = fs::exists(options.out, ec);
  try {
    return writeMerged(options, files, expected_all, fingerprint, summary);
  } catch (...) {
    if (!existed)
      for (const char* suffix : {"", "-wal", "-shm", "-journal"}) fs::remove(options.out + suffix, ec);
    throw;
  }
}

namespace {

MergeSummary writeMerged(const MergeOptions& options, const std::vector<ShardFile>& files,
                         const std::set<std::string>& expected_all, const Fingerprint& fingerprint, MergeSummary summary) {
  namespace fs = std::filesystem;
  const ShardFile& first = files.front();
  ResultsDb out(options.out);
  sqlite3* db = ResultsDbAccess::connection(out);
  const std::string& file = options.out;

  ResultsDbAccess::exec(out, "BEGIN IMMEDIATE");
  try {
    std::set<std::string> stored;  // run keys in the output: before the merge, then as copied
    {
      Statement s(db, "SELECT key FROM runs", file);
      while (s.step()) stored.insert(s.columnText(0));
    }
    std::set<std::string> copied_keys;
    for (const ShardFile& f : files) {
      ReadConnection src(f.path);
      // Runs the output holds already (a merge again, or the same shard in two files) must be the same.
      std::set<std::string> to_copy;
      for (const std::string& k : f.present) {
        if (!stored.count(k)) {
          to_copy.insert(k);
          continue;
        }
        if (runContent(src.db, k, f.path) != runContent(db, k, file))
          throw InputError(f.path, "runs",
                           "run " + k.substr(0, 12) + " has another result than the one already merged (" +
                               (copied_keys.count(k) ? "from another shard file" : "in " + options.out) +
                               "): a planner that is not deterministic?");
        if (copied_keys.count(k)) ++summary.duplicates;
        else ++summary.already_stored;
      }
      auto select = [](const std::string& table, const std::string& key_column) {  // the experiment's rows
        return "SELECT t.* FROM " + table + " t JOIN experiment_runs x ON x.run_key = t." + key_column +
               " WHERE x.experiment_id = ?1";
      };
      {
        // The runs by column name: a database made before a run field was added lacks its column
        // (NULL here), and the output's added columns come last.
        std::string values =
            runFieldExpressions(tableColumns(src.db, "runs", f.path), "t", [](const RunField&) { return true; });
        for (const char* c : kRunContextColumns) values += std::string(", t.") + c;
        copyRows(src,
                 "SELECT " + values + ", t.finished_at FROM runs t JOIN experiment_runs x ON x.run_key = t.key "
                 "WHERE x.experiment_id = ?1",
                 f.experiment, db, "INSERT INTO runs (" + runColumnList() + ") VALUES", file, &to_copy);
      }
      for (const char* table : {"run_repetitions", "metrics", "planner_stats", "planner_timings", "paths", "run_options",
                                "run_car", "run_profile", "run_profile_target", "run_profile_flow", "run_tool_shape", "run_tool_depth", "replans", "replan_figures"}) {
        Statement has(src.db, "SELECT 1 FROM sqlite_master WHERE type = 'table' AND name = ?", f.path);
        has.text(1, table);
        if (!has.step()) continue;  // a shard made before the table (run_profile, run_profile_target): none of its runs has a row
        copyRows(src, select(table, "run_key"), f.experiment, db, std::string("INSERT INTO ") + table + " VALUES", file, &to_copy);
      }
      copyRows(src, "SELECT w.* FROM walls w JOIN experiment_walls x ON x.wall_hash = w.hash WHERE x.experiment_id = ?1",
               f.experiment, db, "INSERT OR IGNORE INTO walls VALUES", file, nullptr);
      copyRows(src,
               "SELECT p.* FROM planner_configs p JOIN experiment_planners x ON x.config_id = p.id WHERE x.experiment_id = ?1",
               f.experiment, db, "INSERT OR IGNORE INTO planner_configs VALUES", file, nullptr);
      summary.copied += to_copy.size();
      copied_keys.insert(to_copy.begin(), to_copy.end());
      stored.insert(to_copy.begin(), to_copy.end());
    }

    // The merged experiment: the shards' config, build and datasets; where and when they ran.
    // Every distinct CPU model, as every host (measured figures of a merge may mix machines).
    std::vector<std::string> cpus;
    std::string started = files.front().started_at, finished, reasons;
    long long executed = 0;
    for (const ShardFile& f : files) {
      cpus.push_back(f.cpu);
      started = std::min(started, f.started_at);
      finished = std::max(finished, f.finished_at);
      executed += f.executed;
      if (!f.rerun_reasons.empty())
        reasons += (reasons.empty() ? "" : "; ") + ("shard " + toString(f.shard) + ": " + f.rerun_reasons);
    }
    const long long total = static_cast<long long>(first.config_runs);
    ReadConnection src(first.path);
    {
      Statement sel(src.db,
                    "SELECT name, config_path, config_text, config_hash, baseline, ?2, git_revision, git_diff_sha256, "
                    "compiler, build_type, build_flags, ?3, ?10, cores, os, memory_bytes, workers, ?4, ?5, ?6, ?7, ?8, 0, ?9 "
                    "FROM experiments WHERE id = ?1",
                    first.path);
      sel.integer(1, first.experiment).text(2, options.command_line).text(3, summary.hosts).text(4, started);
      sel.text(5, finished).integer(6, total).integer(7, std::min(executed, total)).integer(8, std::max(0LL, total - executed));
      sel.text(9, reasons).text(10, joinDistinct(cpus, " / "));
      copyRows(sel, db,
               "INSERT INTO experiments (name, config_path, config_text, config_hash, baseline, command_line, git_revision, "
               "git_diff_sha256, compiler, build_type, build_flags, host, cpu, cores, os, memory_bytes, workers, "
               "started_at, finished_at, runs_total, runs_executed, runs_skipped, runs_reused, rerun_reasons) VALUES",
               file, nullptr);
    }
    const long long id = sqlite3_last_insert_rowid(db);
    auto copyOwnRows = [&](const std::string& columns, const std::string& table) {
      Statement sel(src.db, "SELECT ?2, " + columns + " FROM " + table + " WHERE experiment_id = ?1", first.path);
      sel.integer(1, first.experiment).integer(2, id);
      copyRows(sel, db, "INSERT INTO " + table + " VALUES", file, nullptr);
    };
    copyOwnRows("position, label, source, walls, sha256", "experiment_datasets");
    copyOwnRows("wall_hash, dataset", "experiment_walls");
    copyOwnRows("position, config_id, label", "experiment_planners");
    {  // every wall of the experiment arrived with the shard that ran it
      Statement s(db, "SELECT COUNT(*) FROM experiment_walls e LEFT JOIN walls w ON w.hash = e.wall_hash "
                      "WHERE e.experiment_id = ? AND w.hash IS NULL", file);
      s.integer(1, id);
      s.step();
      if (s.columnInt(0) > 0)
        throw InputError(first.path, "walls", std::to_string(s.columnInt(0)) + " walls of the experiment are in no shard file");
    }
    Statement er(db, "INSERT INTO experiment_runs (experiment_id, run_key) VALUES (?,?)", file);
    for (const std::string& key : expected_all) er.integer(1, id).text(2, key).run();
    Statement ms(db,
                 "INSERT INTO merged_shards (experiment_id, shard_index, shard_count, source, runs, runs_sha256, host, "
                 "workers, started_at, finished_at) VALUES (?,?,?,?,?,?,?,?,?,?)",
                 file);
    for (const ShardFile& f : files) {
      const std::string source = fs::absolute(f.path).string();
      ms.integer(1, id).integer(2, f.shard.index).integer(3, f.shard.count).text(4, source);
      ms.integer(5, static_cast<long long>(f.expected.size())).text(6, fingerprint.at({f.shard.index, source}));
      ms.text(7, f.host).integer(8, f.workers).text(9, f.started_at).text(10, f.finished_at).run();
    }
    ResultsDbAccess::exec(out, "COMMIT");
    summary.experiment_id = id;
  } catch (...) {
    ResultsDbAccess::rollback(out);
    throw;
  }
  return summary;
}

}  // namespace
}  // namespace coverbench
