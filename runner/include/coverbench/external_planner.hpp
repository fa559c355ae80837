#pragma once
/// Planners outside the tree, in any language (docs/external_planners.md): a manifest names the
/// planner, its version, the command that starts it, its parameters and the files whose content
/// identifies its code; the planner process is started once per process that plans (each worker)
/// and answers one problem per line of JSON (protocol 1 or 2: the manifest's) for as many runs as
/// it is given.
///
/// It runs under the limits and statuses of every run: past the time limit its processes are
/// killed (timeout); past the memory limit (its processes together: their cgroup where the memory
/// controller allows one, else their resident sets summed every 10 ms) they are killed
/// (memory_limit); an answer the protocol does not allow, one over kMaxAnswerBytes, or output
/// after an answer, is invalid_output with the reason; a process that dies or exits is crash.
/// After any of these the next run starts a new process. The path it returns is judged like any
/// other. Stopping a planner process kills every process it started (setsid ones included).
#include <cstddef>
#include <string>

#include "coverbench/planner.hpp"

namespace coverbench::external {

/// The newest protocol version this build speaks; it speaks every version from 1. A manifest names
/// its planner's (`coverbench_planner`); requests carry it and answers must repeat it. Version 2
/// adds the tool's shape and flux profile to the request's `tool`; a version-1 request is the same
/// bytes whatever the tool's profile (the planner plans for the disk; the metrics use the profile).
inline constexpr int kProtocolVersion = 2;
/// The longest answer read (bytes); past it the process is killed and the run is invalid_output.
inline constexpr std::size_t kMaxAnswerBytes = std::size_t{64} << 20;
/// The deepest nesting of arrays and objects an answer may have (it needs 3: the answer, its
/// waypoints, a point); checked on the bytes before the line is parsed.
inline constexpr int kMaxAnswerDepth = 16;
/// The most waypoints an answer may hold: the scoring limit (metrics' kMaxScoredWaypoints);
/// checked on the bytes (arrays counted) before the line is parsed.
inline constexpr std::size_t kMaxAnswerWaypoints = 2000000;
/// The most keys (in all its objects: `stats` holds most) and values an answer may hold, checked
/// on the bytes before parsing, so that what the parser builds stays a small multiple of a path
/// at the scoring limit (a 64 MiB line of "1," would be 32 million values).
inline constexpr std::size_t kMaxAnswerKeys = 10000;
inline constexpr std::size_t kMaxAnswerValues = 4 * kMaxAnswerWaypoints + kMaxAnswerKeys;
/// How much of the end of a planner's stderr a plan call keeps (PlanResult::stderr_tail; a run
/// that ends in crash, error or invalid_output stores it). Everything it writes to stderr is also
/// passed on to the host's stderr, as it comes.
inline constexpr std::size_t kStderrTailBytes = 4096;
/// The memory limit of an external planner's processes where no experiment sets one (`plan`,
/// `conformance`, Python's coverbench.plan): the experiments' default, limits.memory_mb 4096.
inline constexpr std::size_t kDefaultMemoryLimitBytes = std::size_t{4096} << 20;

/// Reads a planner manifest: the planner it describes, whose `make` starts (or reuses) its
/// process. Its code identity (PlannerInfo::code_sha256) is the SHA-256 of the manifest and of
/// every file it declares. Throws InputError naming the file, the field and the problem.
PlannerInfo loadManifest(const std::string& path);

/// Loads the manifest and adds its planner to those found by name (addPlanner): refused, with
/// InputError, when a registered planner has its name.
const PlannerInfo& addFromManifest(const std::string& path);

/// A registered planner by name, or a planner outside the tree by its manifest's path (a name
/// ending in .json, loaded and added by addFromManifest); InputError naming `source` otherwise.
const PlannerInfo& plannerNamed(const std::string& name, const std::string& source);

/// The request line for one problem in protocol `protocol` (1 or 2).
std::string requestJson(const Problem& problem, double time_limit_s, long long id, int protocol = 1);
/// Reads an answer line into `result` (status, reason, path, stats); false with the reason in
/// `why` when the protocol does not allow it: not JSON, a duplicate key, nested deeper than
/// kMaxAnswerDepth or holding more than kMaxAnswerWaypoints (both checked before parsing), ...
/// The answer must repeat the request's `protocol`.
bool readAnswer(const std::string& line, long long id, PlanResult& result, std::string& why, int protocol = 1);

/// Stops every planner process this process started, each with every process it started (a
/// worker does this before it exits).
void stopPlannerProcesses();
/// Kills every process started under the run token `run_token` (the environment variable
/// COVERBENCH_RUN_TOKEN, which a planner's processes inherit, and the cgroups named for it),
/// except `spare`: the runner's guardian does this when the runner ends, however it ends.
void killRunProcesses(const std::string& run_token, int spare);

}  // namespace coverbench::external
