#pragma once
/// What a run is, defined once (docs/run_lifecycle.md): its status, its scalar values (one field
/// table, kRunFields, names them with their type, unit and meaning), and what a worker returns
/// with them (metrics, planner statistics, the path, repairs, repetition timings).
///
/// The field table drives every place a run's values travel: the worker pipe
/// (experiments/src/isolation.cpp), the SQLite `runs` columns, the merge's comparison of runs
/// stored in several shards, the CSV/JSON exports, the report's data and its Python reader (which
/// reads the table from the report data). Adding a field is one line of COVERBENCH_RUN_FIELDS.
#include <cmath>
#include <cstddef>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "coverbench/path.hpp"

namespace coverbench {

/// How a run ended (docs/run_lifecycle.md).
enum class RunStatus {
  Ok,               ///< a valid path that covers everything reachable
  Partial,          ///< a path that knowingly leaves reachable parts out (the reason says which)
  NoReachableArea,  ///< the tool fits nowhere on the wall
  InvalidInput,     ///< the planner refused the problem, with a reason
  Timeout,          ///< past the time limit (or the hard deadline: the process was killed)
  MemoryLimit,      ///< past the memory limit
  Crash,            ///< the run's process died (the signal is recorded)
  Error,            ///< the planner failed (an exception, a failure status), with a reason
  InvalidOutput,    ///< the path fails a judge's validity check
  MetricsError,     ///< the path could not be scored
};
/// Every status, in the order tables list them.
inline constexpr RunStatus kRunStatuses[] = {
    RunStatus::Ok,      RunStatus::Partial,     RunStatus::InvalidOutput, RunStatus::MetricsError,
    RunStatus::NoReachableArea, RunStatus::InvalidInput, RunStatus::Timeout, RunStatus::MemoryLimit,
    RunStatus::Crash,   RunStatus::Error};
/// The name stored and shown: "ok", "partial", "no_reachable_area", ...
const char* toString(RunStatus status);
/// The status named `name`; nullopt for a name that is none.
std::optional<RunStatus> parseRunStatus(std::string_view name);
inline std::ostream& operator<<(std::ostream& out, RunStatus status) { return out << toString(status); }
/// Ok and Partial runs have a path.
inline bool hasPath(RunStatus s) { return s == RunStatus::Ok || s == RunStatus::Partial; }
/// Statuses `coverbench run --retry-failed` runs again: failures of the environment, not of the
/// planner's result (timeout, memory_limit, crash, error, metrics_error).
bool isRetryable(RunStatus s);

/// The type of a field's values.
enum class RunFieldType { Text, Status, Bool, Integer, Real };
/// Where a field is exported: nowhere; the run exports (`coverbench runs` CSV/JSON); those and
/// the report's run objects (a measured figure that the report shows as a metric, or not at all,
/// stays out of them).
enum class RunExport { No, Runs, RunsAndReport };

/// One field of a run. Real fields are NaN when not measured (NULL in SQLite, null in JSON,
/// empty in CSV).
struct RunField {
  const char* name;  ///< the column, key and member name everywhere
  RunFieldType type;
  const char* unit;  ///< "m2", "ms", "s", "bytes" or ""
  /// Measured anew by every execution (timings, memory): not compared when the same run is
  /// stored in several shards, and not expected to repeat.
  bool measured;
  /// A column of the run exports (CSV/JSON), after the run's context (dataset, wall, planner,
  /// tool), and (RunsAndReport) of the report's run objects. plan_time_ms and peak_memory_bytes
  /// reach both as metrics instead (they are in the metric registry); the key leads every row.
  RunExport exported;
  const char* description;
};

/// The field table, the one place a run's fields are listed: each line gives the field's name
/// (its member, column and key everywhere), type, C++ type, default, unit, whether it is measured,
/// where it is exported (RunExport), and what it means. RunFields, kRunFields and forEachRunField are all
/// generated from it, so adding a field is one line here.
#define COVERBENCH_RUN_FIELDS(X)                                                                                  \
  X(key, Text, std::string, {}, "", false, No,                                                                   \
    "the run key: what is computed and by what code (docs/run_lifecycle.md)")                                   \
  X(status, Status, RunStatus, RunStatus::Error, "", false, RunsAndReport, "how the run ended")                 \
  X(reason, Text, std::string, {}, "", false, RunsAndReport,                                                     \
    "why a run failed or left parts out (an invalid path: its first violating segments); empty otherwise")     \
  X(valid, Bool, bool, false, "", false, RunsAndReport, "the path passes the validity check")                   \
  X(signal, Integer, long long, 0, "", false, No, "the signal that ended a crashed run's process; 0 otherwise")  \
  X(uncovered_reachable_m2, Real, double, NAN, "m2", false, RunsAndReport,                                       \
    "the reachable area the path did not sweep (metrics engine); NaN when not scored")                          \
  X(plan_time_ms, Real, double, 0.0, "ms", true, No,                                                             \
    "median wall-clock time of the repetitions' plan calls; 0 when no plan call finished")                      \
  X(cpu_time_s, Real, double, NAN, "s", true, Runs,                                                              \
    "user + system CPU time of the run: the worker's for an in-tree planner (planning and scoring); an external " \
    "planner's own processes' during its plan calls")                                                            \
  X(peak_rss_bytes, Real, double, NAN, "bytes", true, No,                                                        \
    "the run's process's peak resident set (an external planner: its processes' summed peaks)")                \
  X(peak_memory_bytes, Real, double, NAN, "bytes", true, No,                                                     \
    "the run's own allocation peak (the worker's allocation meter; without one, peak_rss_bytes - start_rss_bytes; " \
    "an external planner: its processes' peak)")                                                                 \
  X(start_rss_bytes, Real, double, NAN, "bytes", true, No,                                                       \
    "the process's resident set when the run started (inherited from the runner)")                             \
  X(stderr_tail, Text, std::string, {}, "", true, RunsAndReport,                                                 \
    "the last 4 KiB of an external planner's stderr during a crash, error or invalid_output run (bytes that "   \
    "are not UTF-8 replaced by U+FFFD); empty otherwise")

/// The table's fields, in its order (forEachRunField visits the members in this order).
inline constexpr RunField kRunFields[] = {
#define COVERBENCH_RUN_FIELD_ENTRY(name, type, cpp, init, unit, measured, exported, description) \
  {#name, RunFieldType::type, unit, measured, RunExport::exported, description},
    COVERBENCH_RUN_FIELDS(COVERBENCH_RUN_FIELD_ENTRY)
#undef COVERBENCH_RUN_FIELD_ENTRY
};
inline constexpr std::size_t kRunFieldCount = sizeof kRunFields / sizeof kRunFields[0];

/// A run's scalar values: one member per field of the table. RunRecord (what a worker returns)
/// and ResultRow (a run as the tables see it) are both RunFields, so a run's values and their
/// defaults are defined by the table alone.
struct RunFields {
#define COVERBENCH_RUN_FIELD_MEMBER(name, type, cpp, init, unit, measured, exported, description) cpp name = init;
  COVERBENCH_RUN_FIELDS(COVERBENCH_RUN_FIELD_MEMBER)
#undef COVERBENCH_RUN_FIELD_MEMBER
};

/// Calls f(kRunFields[i], member) for every field of `r` in the table's order (`r` const or not).
template <class Fields, class F>
void forEachRunField(Fields& r, F&& f) {
  std::size_t i = 0;
#define COVERBENCH_RUN_FIELD_VISIT(name, type, cpp, init, unit, measured, exported, description) f(kRunFields[i++], r.name);
  COVERBENCH_RUN_FIELDS(COVERBENCH_RUN_FIELD_VISIT)
#undef COVERBENCH_RUN_FIELD_VISIT
}

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
  /// Named figures (NaN when not measured): see kReplanFigures (experiment.hpp).
  std::map<std::string, double> figures;
  Path path;  ///< the repaired path (executed part and repaired remainder)
  std::size_t cut_waypoint = 0;  ///< the index in `path` of the robot's position when the obstacles appeared
};

/// What a run produced: its fields, and what comes with them.
struct RunRecord : RunFields {
  /// The metrics engine's values, in its order; empty unless the run has a scored path.
  std::vector<std::pair<std::string, double>> metrics;
  std::map<std::string, double> stats;       ///< the planner's deterministic statistics
  std::map<std::string, double> timings_ms;  ///< the planner's own sub-timings (measured, first repetition)
  Path path;
  /// `path` as encodePath wrote it, when the record came encoded (from a worker process): the
  /// store writes these bytes instead of compressing the path again. Empty otherwise.
  std::string path_blob;
  std::vector<ReplanRecord> replans;   ///< with replanning: one per fraction and repair, in that order
  std::vector<double> plan_times_ms;   ///< measured: wall-clock of every repetition's plan call
};

}  // namespace coverbench
