#pragma once
/// Sharded experiments: a deterministic partition of an experiment's runs into N shards, each run
/// by its own `coverbench run CONFIG --shard I/N` (a Slurm array task, say) into its own database,
/// and the merge of those databases into one. docs/scaling.md.
#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "coverbench/experiment.hpp"

namespace coverbench {

/// Shard `index` of `count` (0 <= index < count).
struct Shard {
  unsigned index = 0;
  unsigned count = 1;
};
/// The most shards an experiment can be split into (Slurm's default MaxArraySize is 1001).
constexpr unsigned kMaxShards = 100000;

/// Parses "I/N" (0 <= I < N <= kMaxShards). Throws InputError(source, "shard", why).
Shard parseShard(const std::string& text, const std::string& source = "--shard");
/// "I/N".
std::string toString(const Shard& shard);

/// The shard a run belongs to: the first 64 bits of its base key modulo `count`. A pure function
/// of what the run computes: the same on every machine and build, whatever other runs the config
/// has (a grown config moves no run to another shard, so shards resume after it).
unsigned shardOf(const RunSpec& run, unsigned count);

/// OUTPUT/shards/shard-I-of-N.sqlite: where `coverbench run CONFIG --shard I/N` stores its runs.
std::string shardDatabasePath(const ExperimentConfig& config, const Shard& shard);

/// What a shard's experiment row records besides the experiment: which shard, and how many runs
/// the whole config has (so a merge can tell a missing shard from a partition mismatch).
struct ShardRecord {
  Shard shard;
  std::size_t config_runs = 0;
  /// The walls this shard's runs use: only their content is stored in the shard's database (all
  /// walls are listed in experiment_walls), so N shards do not hold N copies of every wall.
  std::set<std::string> wall_hashes;
};

struct MergeOptions {
  std::string out;                  ///< the merged database (new, or an existing results database)
  std::vector<std::string> shards;  ///< shard databases, in any order
  std::string command_line;         ///< recorded in the merged experiment's provenance
};

struct MergeSummary {
  unsigned shard_count = 0;          ///< N of the shards' I/N
  std::size_t shard_files = 0;       ///< files read
  std::size_t runs = 0;              ///< the config's runs (all present, or the merge refuses)
  std::size_t copied = 0;            ///< runs written into the output
  std::size_t already_stored = 0;    ///< runs the output held already (a merge again, or a resumed one)
  std::size_t duplicates = 0;        ///< runs found in more than one shard file (identical, kept once)
  std::vector<std::string> notes;    ///< what a user should know: shards given twice, and so on
  std::string hosts;                 ///< the distinct hosts the shards ran on, comma-separated
  bool unchanged = false;            ///< the output's latest experiment is this merge already: nothing written
  long long experiment_id = 0;       ///< the merged experiment in the output
};

/// Merges shard databases on run key into `options.out`, all in one transaction (nothing is
/// written unless the merge is complete and consistent). Refuses, with an InputError naming the
/// file and the problem: a file that is not a shard database, shards of different configs,
/// builds, datasets or shard counts, a missing shard, runs missing from a shard (killed and not
/// resumed), and runs stored twice with different results. Idempotent: merging the same shards
/// again changes nothing.
MergeSummary mergeShards(const MergeOptions& options);

}  // namespace coverbench
