#pragma once
/// Runs an experiment: every run not already in the results database, in parallel on worker
/// threads; one writer stores each finished run in its own transaction.
#include <cstdio>
#include <map>
#include <optional>
#include <string>

#include "coverbench/experiment.hpp"
#include "coverbench/shards.hpp"

namespace coverbench {

struct RunnerOptions {
  unsigned threads = 0;            ///< runs at once (worker processes); 0: the config's, or every core
  std::FILE* progress = nullptr;   ///< where progress goes (a bar on a terminal, lines otherwise)
  bool timing = false;             ///< one run at a time, so timings do not share the machine
  bool retry_failed = false;       ///< run stored timeouts, memory_limits, crashes and errors again
  bool reuse_across_builds = false;  ///< count a stored run of another planner version or code as done
  std::string command_line;        ///< recorded in the experiment's provenance
  /// Only this shard's runs (shardOf), stored in shardDatabasePath instead of the results database.
  std::optional<Shard> shard;
};

struct RunnerSummary {
  std::size_t total = 0;         ///< the runs this invocation is responsible for (a shard's share)
  std::size_t config_runs = 0;   ///< the config's runs (all shards)
  std::size_t executed = 0;
  std::size_t skipped = 0;  ///< already in the database
  std::size_t reused = 0;   ///< stored by another build, reused (reuse_across_builds)
  std::string rerun_reasons;  ///< why stored runs of the same work were run again, e.g. "12 zigzag: planner version changed"
  std::map<std::string, std::size_t> by_status;  ///< executed runs per status
  std::size_t walls = 0;
  double seconds = 0.0;
  unsigned threads = 0;
  std::string database;
  long long experiment_id = 0;
};

/// The database file inside an experiment's output folder.
std::string resultsDatabasePath(const ExperimentConfig& config);

RunnerSummary runExperiment(const ExperimentConfig& config, const RunnerOptions& options);

/// Executes one run as the runner does: in a worker process of its own, under the run's limits
/// (time limit, hard deadline, memory), and returns its record (a timeout, crash or memory_limit
/// when the worker did not answer in time or died). For callers that must not run planners in
/// their own process (the explorer's workbench).
RunRecord executeInWorker(const RunSpec& spec);
/// A run record as bytes and back (what a worker sends through its pipe). deserializeRecord
/// throws std::runtime_error on malformed bytes.
std::string serializeRecord(const RunRecord& record);
RunRecord deserializeRecord(const std::string& bytes);

}  // namespace coverbench
