#pragma once
/// Experiments: a YAML config expanded into runs; a run is a pure function of (wall, planner
/// configuration, tool parameters, seed), so it can later move into a child process or onto a
/// cluster node without changing what it computes.
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "coverbench/metrics.hpp"
#include "coverbench/param_codec.hpp"
#include "coverbench/planner.hpp"
#include "coverbench/published.hpp"
#include "coverbench/replanning.hpp"
#include "coverbench/run_planner.hpp"
#include "coverbench/run_record.hpp"
#include "coverbench/wall.hpp"
#include "coverbench/wall_import.hpp"

namespace coverbench {

/// Where walls come from: a generator family (count, seed), a fixed suite, or a folder.
struct DatasetSpec {
  enum class Kind { Family, Suite, Folder, Import } kind = Kind::Family;
  std::string family;  ///< family or suite name
  std::size_t count = 0;  ///< walls: as given for a family; the suite's size; a folder's .json files
  std::uint64_t seed = 0;
  std::string folder;  ///< resolved against the config file's folder (a folder, or what `import` names)
  ImportOptions import_options;  ///< for `import:` (docs/datasets.md)
  /// For `import:`: the walls, imported once when the config is loaded.
  std::shared_ptr<const std::vector<Wall>> imported;
  /// Where the paths on these walls begin and end (`start:`, `end:`), for walls that name none.
  std::optional<Point> start, end;
  bool end_at_start = false;  ///< `end: start`: each wall's own start, or the dataset's
  std::string label;   ///< the name tables group by (family, suite, or folder name)
  int line = 0;        ///< 1-based line in the config, for messages
};

/// One planner with one set of parameter values (sweeps are expanded into several of these).
struct PlannerConfig {
  std::string planner;
  ParamSettings settings;  ///< as given (each read once), in key order
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
  /// How the robot carries the tool (config section `vehicle:`; holonomic when absent). One per
  /// experiment, so no table pools two models: compare them with two experiments.
  VehicleModel vehicle;
  /// The time model of duration_s (config section `motion:`; the default when absent). One per
  /// experiment: a report's durations all mean the same clock.
  MotionLimits motion;
  /// How planners find their tool-off detours (config section `transit:`; visibility when absent):
  /// one run per transit planner listed, compared side by side like tool widths (never pooled).
  /// Sampling planners are seeded from `seed`.
  std::vector<TransitSpec> transits{TransitSpec{}};
  /// Obstacles that appear while paths are executed, and how they are repaired (config section
  /// `replanning:`; off when absent). Every run with a valid path gets one record per fraction and
  /// repair (docs/replanning.md).
  ReplanningSpec replanning;
  int repetitions = 1;
  double time_limit_s = 60.0;
  double memory_limit_mb = 4096.0;
  std::string baseline;     ///< a planner label; default: the first
  unsigned threads = 0;     ///< 0: every core
  std::uint64_t seed = 0;   ///< passed to planners (Problem::seed)
  bool allow_large = false; ///< confirms an experiment of more than kLargeExperimentRuns runs
  /// Also score every path with the exact judge (judge/), config key `judge: exact`: its verdict
  /// and certified coverage intervals are stored as the exact_* metrics, and a path only it finds
  /// invalid is `invalid_output`.
  bool exact_judge = false;
  /// Published values to set beside the planners in the report (config section `published:`;
  /// none when absent): read and checked with the config.
  std::optional<PublishedTable> published;
};

/// The number of runs a config asks for (walls counted before loading, duplicates included, times
/// runsPerWall; a run's repetitions are one run): known before any wall is generated, so a huge
/// experiment is caught at once.
std::size_t plannedRuns(const ExperimentConfig& config);

/// Reads and checks a config completely (planner names, parameter values against their
/// declarations, families, folders) before anything runs. Errors throw InputError whose source
/// is `FILE:LINE` and whose field is the key path, e.g. `planners[1].params.sweep_angle`.
ExperimentConfig loadExperimentConfig(const std::string& path);
/// The time model a config's text sets (its `motion:` section; the default without one), for
/// readers of a stored experiment. `source` names it in errors.
MotionLimits configMotion(const std::string& config_text, const std::string& source);
/// The flux profile a config's text gives its tools (`tool.profile`, checked for a tool
/// `tool_width` wide; none without one), for readers of a stored experiment.
FluxProfile configProfile(const std::string& config_text, const std::string& source, double tool_width);

/// The published table a config's text names (its `published:` section, the table's path
/// relative to `source`'s folder), read and checked; none without one. For the report of a stored
/// experiment.
std::optional<PublishedTable> configPublished(const std::string& config_text, const std::string& source);
/// The published table `table` with the clock `clock` as `coverbench report --published-clock`
/// gives it: `unknown`, or a YAML mapping with the keys of `motion:` ('{speed: 0.3}').
PublishedTable publishedTable(const std::string& table, const std::string& clock);

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
  VehicleModel vehicle;
  MotionLimits motion;  ///< the time model of its duration_s (in the base key when not the default)
  TransitSpec transit;
  ReplanningSpec replanning;  ///< off unless the config has a `replanning:` section
  int repetitions = 1;  ///< the plan is executed this many times in the run's process, each timed
  std::uint64_t seed = 0;
  double time_limit_s = 60.0;
  std::size_t memory_limit_bytes = 0;  ///< 0: none
  std::string planner_version;         ///< the planner's declared version
  std::string code_sha256;             ///< BuildIdentity::plannerCode of the planner's folders
  bool exact_judge = false;            ///< also scored by the exact judge (in the base key when set)
  std::string base_key;                ///< what the run computes: see runKey
  std::string key;                     ///< base key, planner version and code: see runKey
};
/// The base key: SHA-256 of the wall's content hash, the planner, every resolved parameter
/// (defaults included), the tool parameters, the seed, and (only when set) the exact judge, a
/// vehicle other than holonomic, a transit planner other than visibility with its iterations,
/// replanning, and a time model other than the default (so keys from before vehicle models,
/// transit planners, replanning and time models are unchanged).
/// Limits and repetitions are not in it.
std::string runBaseKey(const RunSpec& spec);
/// The run key: SHA-256 of the base key, the planner's version and its code identity, so a
/// changed planner (or the code every run depends on, or the compiler and flags) is run again.
std::string runKey(const RunSpec& spec);
/// The runs a config asks for per wall: one per planner configuration, tool and transit planner
/// (every axis of a run but the wall). expandRuns expands exactly these; plannedRuns counts them.
std::size_t runsPerWall(const ExperimentConfig& config);
/// Every (wall, planner configuration, tool, transit planner) of the config, keys filled in, in a
/// fixed order; with `keep`, only the runs it accepts (it sees the base key; the run key is filled
/// in after). `expanded`, when given, receives how many runs were expanded before `keep` chose:
/// the config's count of runs over these walls, whatever the filter.
std::vector<RunSpec> expandRuns(const ExperimentConfig& config, const std::vector<WallEntry>& walls,
                                const std::function<bool(const RunSpec&)>& keep = {}, std::size_t* expanded = nullptr);

/// The figures of a ReplanRecord, in the order tables show them.
inline constexpr const char* kReplanFigures[] = {
    "executed_m",               // length executed before the obstacles appeared
    "added_length_m",           // repaired path's length minus the original path's
    "added_duration_s",         // the same for duration_s
    "coverage_reachable",       // of the repaired path, on the new wall
    "scratch_coverage_reachable",  // of a plan made from scratch on the new wall (same planner)
    "scratch_length_m",         // that plan's length
    "uncovered_added_m2",       // reachable area left unpainted after the repair, minus what the original path left
    "blocked_m",                // detour: painting length the obstacles block
    "kept_moves", "dropped_moves", "unreachable_moves", "transits",  // Repair's counts
};

/// Executes one run in this process: plan under the time budget (`repetitions` times, each
/// timed; the first result is kept), then score the path with the metrics engine. The runner
/// calls it in a child process per run (hard limits, rusage); tests may call it directly.
RunRecord executeRun(const RunSpec& spec);


/// Path storage: little-endian doubles and tool flags, then (only for a path with arcs) one bulge
/// per segment, zlib-compressed ("zlib-f64le-1").
std::string encodePath(const Path& path);
/// Throws InputError ("path blob", "data", why) for a corrupt blob, before allocating more than
/// its contents can expand to.
Path decodePath(const std::string& blob);

}  // namespace coverbench
