#pragma once
/// Planners outside the tree, in any language (docs/external_planners.md): a manifest names the
/// planner, its version, the command that starts it, its parameters and the files whose content
/// identifies its code; the planner process is started once per process that plans (each worker)
/// and answers one problem per line of JSON (protocol 1) for as many runs as it is given.
///
/// It runs under the limits and statuses of every run: past the time limit its process group is
/// killed (timeout); past the memory limit (its resident set, read every 10 ms) it is killed
/// (memory_limit); an answer the protocol does not allow, or one over kMaxAnswerBytes, is
/// invalid_output with the reason; a process that dies or exits is crash. After any of these the
/// next run starts a new process. The path it returns is judged like any other.
#include <cstddef>
#include <string>

#include "coverbench/planner.hpp"

namespace coverbench::external {

/// The protocol version this build speaks (requests carry it; answers must repeat it).
inline constexpr int kProtocolVersion = 1;
/// The longest answer read (bytes); past it the process is killed and the run is invalid_output.
inline constexpr std::size_t kMaxAnswerBytes = std::size_t{64} << 20;

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

/// The request line for one problem (protocol 1; tests and benchmarks).
std::string requestJson(const Problem& problem, double time_limit_s, long long id);
/// Reads an answer line into `result` (status, reason, path, stats); false with the reason in
/// `why` when the protocol does not allow it.
bool readAnswer(const std::string& line, long long id, PlanResult& result, std::string& why);

}  // namespace coverbench::external
