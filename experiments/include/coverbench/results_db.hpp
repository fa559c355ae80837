#pragma once
/// Experiment results in SQLite (WAL): experiments, walls, planner configurations, runs with every
/// metric, planner statistics and the compressed path of each run. One transaction per run, so a
/// killed experiment loses at most the runs in flight. Schema: docs/file_formats.md.
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>

#include "coverbench/experiment.hpp"
#include "coverbench/records.hpp"
#include "coverbench/shards.hpp"

struct sqlite3;

namespace coverbench {

class Statement;

/// Facts about the machine and build that produced results (docs/run_lifecycle.md).
struct Provenance {
  std::string git_revision, git_diff_sha256, compiler, build_type, build_flags;  ///< buildIdentity()
  std::string host, cpu, os;  ///< host name; CPU model; distribution, kernel release and machine
  unsigned cores = 0;
  double memory_bytes = NAN;  ///< physical memory
  std::string command_line;
  std::string started_at;  ///< UTC, ISO 8601
  unsigned workers = 0;    ///< runs executed at once
};
Provenance currentProvenance(unsigned workers, const std::string& command_line);
/// Now, UTC, ISO 8601 ("2026-11-26T23:55:15Z"): how the databases store when something happened.
std::string utcNow();

class ResultsDb {
 public:
  /// ReadWrite opens or creates a database to store runs in; ReadOnly (for reading commands)
  /// never writes, and the file must exist.
  enum class Mode { ReadWrite, ReadOnly };
  /// Opens the database. An existing file must be CoverBench's (its application_id, or the
  /// tables of the first schema) and of a schema this build knows; it is checked before anything
  /// is written. Throws InputError naming the file on failure.
  explicit ResultsDb(const std::string& path, Mode mode = Mode::ReadWrite);
  ~ResultsDb();
  ResultsDb(const ResultsDb&) = delete;
  ResultsDb& operator=(const ResultsDb&) = delete;

  /// Records the experiment, its provenance, datasets (with content hashes), walls and planner
  /// configurations, which stored runs belong to it, and for a shard which shard it is. Returns
  /// its id.
  long long beginExperiment(const ExperimentConfig& config, const Provenance& provenance,
                            const std::vector<WallEntry>& walls, const std::vector<std::string>& run_keys,
                            const ShardRecord* shard = nullptr);
  /// A stored run's identity: its key, the key without planner version and code, and those two.
  struct StoredKey {
    std::string key, base_key, planner_version, code_sha256;
    RunStatus status = RunStatus::Error;
  };
  std::vector<StoredKey> storedKeys();
  /// Stores one run in one transaction.
  void storeRun(const RunSpec& spec, const RunRecord& record);
  void finishExperiment(long long id, std::size_t executed, std::size_t skipped, std::size_t reused,
                        const std::string& rerun_reasons);

  /// Every experiment in the file, oldest first: id, name and how many runs belong to it.
  struct ExperimentEntry {
    long long id = 0;
    std::string name;
    long long runs = 0;
  };
  std::vector<ExperimentEntry> experiments();
  /// One run of an experiment as a browser of 10^5 runs lists it: its context, status and the
  /// two measured figures the runs table holds; metrics come by column (metricColumn) or by run
  /// (metricsOf), so listing an experiment does not read every metric of every run.
  struct RunSummary {
    std::string key, planner, dataset, wall, wall_name;  ///< planner: the experiment's label
    RunStatus status = RunStatus::Error;
    ToolParams tool;
    double plan_time_ms = NAN, peak_memory_bytes = NAN;
  };
  /// The experiment's runs in key order. Throws InputError when there is no such experiment.
  std::vector<RunSummary> runSummaries(long long experiment);
  /// The names of the metrics stored for the experiment's runs, in the engine's order, then
  /// plan_time_ms and peak_memory_bytes (as load()'s metric_order): those of one scored run per
  /// build, which stores the same names for every scored run.
  std::vector<std::string> metricNames(long long experiment);
  /// One metric of every run of the experiment, in runSummaries' order; NaN where a run has none
  /// (failed runs; NULL, as infinities are stored).
  std::vector<double> metricColumn(long long experiment, const std::string& metric);
  /// Every stored metric of each run named (finite values only), with plan_time_ms and
  /// peak_memory_bytes.
  std::map<std::string, std::map<std::string, double>> metricsOf(const std::vector<std::string>& run_keys);
  /// The runs of one experiment (default: the latest) as the tables see them.
  ResultSet load(std::optional<long long> experiment = std::nullopt);
  /// The experiment's record (config, provenance, datasets, planner configurations, walls) for
  /// reports; the same experiment as load().
  ExperimentRecord record(std::optional<long long> experiment = std::nullopt);
  /// The stored path of a run.
  std::optional<Path> path(const std::string& run_key);

  /// Everything needed to redraw one run.
  struct StoredRun {
    std::string key;
    Wall wall;
    std::string planner;  ///< planner name and resolved parameters
    std::string planner_name;  ///< the registered planner
    std::string params_json;   ///< its resolved parameters as stored: a JSON object
    /// Width and clearance; the flux profile and `motion` are the config's of the latest
    /// experiment that holds the run (the run key holds both, so every such experiment agrees).
    ToolParams tool;
    MotionLimits motion;
    VehicleModel vehicle;
    std::string status, reason;  ///< the run's (RunStatus's name) or the repair's
    std::string stderr_tail;     ///< the run's (RunRecord::stderr_tail; "" in a database from before it)
    Path path;  ///< empty when the run failed
    /// A repair (storedReplan): segments before it were driven before the obstacles appeared.
    std::size_t first_judged_segment = 0;
  };
  /// The run whose key starts with `key_prefix` (at least 6 characters); throws InputError when
  /// none or several match.
  StoredRun storedRun(const std::string& key_prefix);
  /// The repair number `position` (0-based, in the order of the replans table) of that run: the
  /// wall with the obstacles that appeared, the repaired path, the repair's status and reason;
  /// `planner` names the fraction and the repair. Throws InputError when the run has no such repair.
  StoredRun storedReplan(const std::string& key_prefix, std::size_t position);

  /// Caps the database's size (SQLite's max_page_count), so tests can make a write fail as a full
  /// disk would.
  void limitPagesForTesting(long long pages);

 private:
  friend struct ResultsDbAccess;  // merge.cpp: copies rows through the connection, in one transaction
  void exec(const std::string& sql);
  /// The file's application id and schema version, read before anything is written.
  struct Marks {
    long long application_id = 0;
    long long version = 0;
  };
  /// Refuses (InputError) a file that is not a CoverBench results database of this schema; read
  /// only, also one with nothing in it.
  Marks checkOwnership(Mode mode);
  /// The columns of the runs table.
  std::set<std::string> runColumns();
  /// Adds the columns of run fields an older database lacks (opened for writing).
  void addMissingRunColumns();
  /// The run fields as SELECT expressions on the runs table `alias`, in kRunFields' order (NULL
  /// for a field the database has no column for).
  std::string runFieldSelect(const std::string& alias);
  void rollback() noexcept;
  /// A statement prepared once per connection and reset for each use: storing a run runs about
  /// twenty, and preparing them anew was about a fifth of the storing process's CPU (perf).
  Statement& prepared(const std::string& sql);
  sqlite3* db_ = nullptr;
  std::string file_;
  std::map<std::string, std::unique_ptr<Statement>> prepared_;  ///< finalized before the connection closes
};

}  // namespace coverbench
