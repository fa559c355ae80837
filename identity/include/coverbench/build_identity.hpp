#pragma once
/// What built this binary, captured at every build by cmake/build_identity.cmake: the git
/// revision and a hash of the uncommitted diff (provenance), the compiler, build type and flags,
/// and content hashes of the code (run keys). docs/run_lifecycle.md says what changes a run key.
#include <map>
#include <string>
#include <vector>

namespace coverbench {

struct BuildIdentity {
  std::string git_revision;       ///< "unknown" outside a git checkout
  std::string dirty_diff_sha256;  ///< SHA-256 of `git diff HEAD`; empty when the tree is clean
  std::string compiler;           ///< id and version, e.g. "GNU 12.2.0"
  std::string build_type;         ///< e.g. "Release"
  std::string flags;              ///< the C++ flags of that build type
  /// SHA-256 over the code every run depends on: base/, identity/, files/, geometry/, formats/,
  /// transits/, planning/, vehicles/, metrics/, algorithms/*.cpp, runner/, the run execution and
  /// replanning in experiments/
  /// (runs.cpp, isolation.cpp, replanning.cpp); cmake/build_identity.cmake lists them.
  std::string shared_code_sha256;
  /// SHA-256 over each algorithms/<folder>'s .cpp and .hpp files, and over the exact judge's
  /// (judge/) under the name kJudgeCodeFolder.
  std::map<std::string, std::string> folder_code_sha256;

  /// The identity of a planner's code: SHA-256 of the shared code, the given algorithms/
  /// folders' code, the compiler, build type and flags. A folder that is not one throws
  /// std::logic_error (a misspelt code_folders entry must not hash as empty).
  std::string plannerCode(const std::vector<std::string>& folders) const;
  /// "rev12[-dirty:diff12]": for people.
  std::string describe() const;
};

/// The name of the exact judge's code in folder_code_sha256 (no algorithms/ folder can have it).
inline constexpr const char* kJudgeCodeFolder = ":judge";

/// This binary's identity (generated source).
const BuildIdentity& buildIdentity();

}  // namespace coverbench
