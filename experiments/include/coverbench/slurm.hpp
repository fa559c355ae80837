#pragma once
/// Slurm job scripts for a sharded experiment: a job array whose task I runs
/// `coverbench run CONFIG --shard I/N`, and a merge job (merge, then report) that runs after it.
/// docs/scaling.md.
#include <string>

#include "coverbench/experiment.hpp"

namespace coverbench {

struct SlurmOptions {
  unsigned shards = 8;         ///< array tasks, one shard each
  unsigned cpus_per_task = 1;  ///< each task's worker processes (`--threads`)
  unsigned throttle = 0;       ///< at most this many tasks at once (the array's %K); 0: no limit
  std::string partition;       ///< empty: the cluster's default
  std::string time = "04:00:00";  ///< per task, in Slurm's format
  std::string mem;             ///< per task; empty: the config's memory limit per worker plus 1 GiB
  std::string account;         ///< empty: none
  bool report = true;          ///< the merge job also writes the HTML report
  std::string binary;          ///< the coverbench executable (absolute path)
  std::string workdir;         ///< where the jobs start (absolute path)
};

struct SlurmScripts {
  std::string folder;        ///< OUTPUT/slurm
  std::string run_script;    ///< OUTPUT/slurm/run.sbatch
  std::string merge_script;  ///< OUTPUT/slurm/merge.sbatch
  std::string run_text, merge_text;
};

/// Checks the options (InputError naming the option) and writes nothing: the scripts' text.
SlurmScripts slurmScripts(const ExperimentConfig& config, const SlurmOptions& options);

/// A word quoted for a POSIX shell ('...' with embedded quotes escaped).
std::string shellQuote(const std::string& word);

}  // namespace coverbench
