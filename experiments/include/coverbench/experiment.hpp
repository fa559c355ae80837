#pragma once
/// Experiments: a YAML config expanded into runs; a run is a pure function of (wall, planner
/// configuration, tool parameters, seed), so it can later move into a child process or onto a
/// cluster node without changing what it computes.
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "coverbench/metrics.hpp"
#include "coverbench/planner.hpp"
#include "coverbench/wall.hpp"

namespace coverbench {

/// Where walls come from: a generator family (count, seed), a fixed suite, or a folder.
struct DatasetSpec {
  enum class Kind { Family, Suite, Folder } kind = Kind::Family;
  std::string family;  ///< family or suite name
  std::size_t count = 0;  ///< walls: as given for a family; the suite's size; a folder's .json files
  std::uint64_t seed = 0;
  std::string folder;  ///< resolved against the config file's folder
  std::string label;   ///< the name tables group by (family, suite, or folder name)
  int line = 0;        ///< 1-based line in the config, for messages
};

/// One planner with one set of parameter values (sweeps are expanded into several of these).
struct PlannerConfig {
  std::string planner;
  std::vector<std::pair<std::string, std::string>> settings;  ///< as given, in key order
  Params params;      ///< resolved, with defaults
  std::string label;  ///< "zigzag" or "zigzag(sweep_angle=90)": names it in tables
  std::string id;     ///< content hash of planner name and resolved parameters
};

struct ExperimentConfig {
  std::string path;         ///< the config file
  std::string text;         ///< its bytes
  std::string hash;         ///< SHA-256 of the bytes
  std::string name;
  std::string output;       ///< output folder, resolved against the config file's folder
  std::vector<DatasetSpec> datasets;
  std::vector<PlannerConfig> planners;
  std::vector<ToolParams> tools;  ///< product of the tool widths and clearances given
  int repetitions = 1;
  double time_limit_s = 60.0;
  double memory_limit_mb = 4096.0;
  std::string baseline;     ///< a planner label; default: the first
  unsigned threads = 0;     ///< 0: every core
  std::uint64_t seed = 0;   ///< passed to planners (Problem::seed)
  bool allow_large = false; ///< confirms an experiment of more than kLargeExperimentRuns runs
};

/// The number of runs a config asks for (walls counted before loading, duplicates included):
/// known before any wall is generated, so a huge experiment is caught at once.
std::size_t plannedRuns(const ExperimentConfig& config);

/// Reads and checks a config completely (planner names, parameter values against their
/// declarations, families, folders) before anything runs. Errors throw InputError whose source
/// is `FILE:LINE` and whose field is the key path, e.g. `planners[1].params.sweep_angle`.
ExperimentConfig loadExperimentConfig(const std::string& path);

/// A wall as a run sees it: its content (canonical JSON) and hash, and the dataset it came from.
struct WallEntry {
  Wall wall;
  std::string json;
  std::string hash;
  std::string dataset;
};
/// Generates or reads every dataset of the config (in config order; duplicates by content kept
/// once, under the first dataset that brought them).
std::vector<WallEntry> loadWalls(const ExperimentConfig& config);

/// One run: everything that determines its result.
struct RunSpec {
  const WallEntry* wall = nullptr;
  const PlannerConfig* planner = nullptr;
  ToolParams tool;
  int repetition = 0;
  std::uint64_t seed = 0;
  double time_limit_s = 60.0;
  std::size_t memory_limit_bytes = 0;  ///< 0: none
  std::string key;                     ///< stable: see runKey
};
/// SHA-256 of the wall hash, planner, resolved parameters, tool parameters, repetition and seed.
std::string runKey(const RunSpec& spec);
/// Every (wall, planner configuration, tool, repetition) of the config, keys filled in, in a
/// fixed order.
std::vector<RunSpec> expandRuns(const ExperimentConfig& config, const std::vector<WallEntry>& walls);

/// What a run produced.
struct RunRecord {
  std::string key;
  /// ok, partial (knowingly left reachable parts out), no_reachable_area, invalid_input, timeout,
  /// memory_limit, crash, error, invalid_output (the path fails the exact check), metrics_error
  /// (the path could not be scored). docs/run_lifecycle.md.
  std::string status;
  std::string reason;
  bool valid = false;
  /// The reachable area the path did not sweep (m²), measured by the metrics engine: what a
  /// partial run left out, in numbers. NaN when not scored.
  double uncovered_reachable_m2 = NAN;
  double plan_time_ms = 0.0;
  std::optional<double> peak_memory_bytes;
  std::vector<NamedMetric> metrics;  ///< empty unless status is ok
  std::map<std::string, double> stats;       ///< the planner's deterministic statistics
  std::map<std::string, double> timings_ms;  ///< the planner's own sub-timings (measured)
  Path path;
};

/// Measures (and limits) heap use around a plan call, on the calling thread. The coverbench
/// binary provides one; without it, peak memory is not measured and not limited.
struct MemoryProbe {
  std::function<void(std::size_t limit_bytes)> begin;
  std::function<std::size_t()> end;   ///< peak bytes since begin
  std::function<bool()> limit_hit;    ///< whether the limit made an allocation fail
};

/// Executes one run: plan under the time budget, then score the path with the metrics engine.
RunRecord executeRun(const RunSpec& spec, const MemoryProbe* probe);

/// Path storage: little-endian doubles and tool flags, zlib-compressed ("zlib-f64le-1").
std::string encodePath(const Path& path);
/// Throws InputError ("path blob", "data", why) for a corrupt blob, before allocating more than
/// its contents can expand to.
Path decodePath(const std::string& blob);

}  // namespace coverbench
