#pragma once
/// Runs an experiment: every run not already in the results database, in parallel on worker
/// threads; one writer stores each finished run in its own transaction.
#include <cstdio>
#include <string>

#include "coverbench/experiment.hpp"

namespace coverbench {

struct RunnerOptions {
  unsigned threads = 0;               ///< 0: the config's value, or every core
  std::FILE* progress = nullptr;      ///< where progress goes (a bar on a terminal, lines otherwise)
  const MemoryProbe* probe = nullptr; ///< per-thread heap measurement and limit, if available
};

struct RunnerSummary {
  std::size_t total = 0;
  std::size_t executed = 0;
  std::size_t skipped = 0;  ///< already in the database
  std::size_t walls = 0;
  double seconds = 0.0;
  unsigned threads = 0;
  std::string database;
  long long experiment_id = 0;
};

/// The database file inside an experiment's output folder.
std::string resultsDatabasePath(const ExperimentConfig& config);

RunnerSummary runExperiment(const ExperimentConfig& config, const RunnerOptions& options);

}  // namespace coverbench
