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
#include "coverbench/replanning.hpp"
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
  /// How the robot carries the tool (config section `vehicle:`; holonomic when absent). One per
  /// experiment, so no table pools two models: compare them with two experiments.
  VehicleModel vehicle;
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
};

/// The number of runs a config asks for (walls counted before loading, duplicates included, times
/// runsPerWall; a run's repetitions are one run): known before any wall is generated, so a huge
/// experiment is caught at once.
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
  VehicleModel vehicle;
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
/// vehicle other than holonomic, a transit planner other than visibility with its iterations, and
/// replanning (so keys from before vehicle models, transit planners and replanning are unchanged).
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

/// One repair of a run's path (docs/replanning.md): obstacles appeared at `fraction` of its
/// length and the rest was repaired by `repair`. The repaired path is scored on the new wall by the
/// metrics engine like any path; the figures compare it with the original path and with a plan
/// made from scratch with the obstacles known.
struct ReplanRecord {
  double fraction = 0.0;
  std::string repair;  ///< replan or detour
  std::size_t obstacles = 0;   ///< that appeared
  std::size_t requested = 0;   ///< that were asked for (more than appeared: no place found)
  std::string obstacles_json;  ///< what appeared, as a wall file's obstacles array
  /// ok; partial (the repair knowingly left painting out: blocked stretches of passes, moves no
  /// transit reached, or a new plan that was itself partial); failed (no repaired path: the
  /// reason says why); invalid_output (the metrics engine, or the exact judge with `judge: exact`,
  /// finds the repaired path invalid on the new wall).
  std::string status;
  std::string reason;
  bool valid = false;
  double repair_ms = NAN;  ///< measured: replan includes its plan call; detour its routing
  /// Named figures (NaN when not measured): see kReplanFigures.
  std::map<std::string, double> figures;
  Path path;  ///< the repaired path (executed part and repaired remainder)
  std::size_t cut_waypoint = 0;  ///< the index in `path` of the robot's position when the obstacles appeared
};
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

/// What a run produced.
struct RunRecord {
  std::string key;
  /// ok, partial (knowingly left reachable parts out), no_reachable_area, invalid_input, timeout,
  /// memory_limit, crash (with the signal), error, invalid_output (the path fails the exact
  /// check), metrics_error (the path could not be scored). docs/run_lifecycle.md.
  std::string status;
  std::string reason;
  bool valid = false;
  /// The reachable area the path did not sweep (m²), measured by the metrics engine: what a
  /// partial run left out, in numbers. NaN when not scored.
  double uncovered_reachable_m2 = NAN;
  int signal = 0;                    ///< the signal that ended a crashed run's process
  std::vector<NamedMetric> metrics;  ///< empty unless the run has a scored path
  std::map<std::string, double> stats;       ///< the planner's deterministic statistics
  std::map<std::string, double> timings_ms;  ///< the planner's own sub-timings (measured, first repetition)
  Path path;
  std::vector<ReplanRecord> replans;  ///< with replanning: one per fraction and repair, in that order
  // Measured: a rerun measures these anew.
  std::vector<double> plan_times_ms;  ///< wall-clock of every repetition's plan call
  double plan_time_ms = 0.0;          ///< their median
  double cpu_time_s = NAN;            ///< user + system CPU of the run's process (rusage)
  double peak_rss_bytes = NAN;        ///< the run's process's peak resident set (rusage)
  double start_rss_bytes = NAN;       ///< its resident set when the run started (inherited from the runner)
  /// The run's own peak: the highest sum of its live C++ allocations (the worker's allocation
  /// meter, experiments/src/allocation_meter.cpp); where no meter is built in (AddressSanitizer),
  /// peak_rss_bytes - start_rss_bytes.
  std::optional<double> peak_memory_bytes;
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
