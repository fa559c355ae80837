#pragma once
/// Experiment results in SQLite (WAL): experiments, walls, planner configurations, runs with every
/// metric, planner statistics and the compressed path of each run. One transaction per run, so a
/// killed experiment loses at most the runs in flight. Schema: docs/file_formats.md.
#include <memory>
#include <optional>
#include <set>
#include <string>

#include "coverbench/experiment.hpp"
#include "coverbench/tables.hpp"

struct sqlite3;

namespace coverbench {

/// Facts about the machine and build that produced results.
struct Provenance {
  std::string git_revision;
  std::string compiler;
  std::string cpu;
  std::string started_at;  ///< UTC, ISO 8601
  unsigned threads = 0;
};
Provenance currentProvenance(unsigned threads);

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

  /// Records the experiment, its walls and planner configurations, and which runs belong to it.
  /// Returns its id.
  long long beginExperiment(const ExperimentConfig& config, const Provenance& provenance,
                            const std::vector<WallEntry>& walls, const std::vector<RunSpec>& runs);
  /// Keys of runs already stored (finished, with any status).
  std::set<std::string> finishedRuns();
  /// Stores one run in one transaction.
  void storeRun(const RunSpec& spec, const RunRecord& record);
  void finishExperiment(long long id, std::size_t executed, std::size_t skipped);

  /// The runs of one experiment (default: the latest) as the tables see them.
  ResultSet load(std::optional<long long> experiment = std::nullopt);
  /// The stored path of a run.
  std::optional<Path> path(const std::string& run_key);

  /// Everything needed to redraw one run.
  struct StoredRun {
    std::string key;
    Wall wall;
    std::string planner;  ///< planner name and resolved parameters
    ToolParams tool;
    std::string status, reason;
    Path path;  ///< empty when the run failed
  };
  /// The run whose key starts with `key_prefix` (at least 6 characters); throws InputError when
  /// none or several match.
  StoredRun storedRun(const std::string& key_prefix);

  /// Caps the database's size (SQLite's max_page_count), so tests can make a write fail as a full
  /// disk would.
  void limitPagesForTesting(long long pages);

 private:
  void exec(const std::string& sql);
  void checkOwnership();
  void rollback() noexcept;
  sqlite3* db_ = nullptr;
  std::string file_;
};

}  // namespace coverbench
