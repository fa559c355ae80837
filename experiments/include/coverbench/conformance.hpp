#pragma once
/// The conformance checks, defined once: which walls and tools they use, what a correct planner
/// must do on each (the expected outcome), and whether one judged plan did it. `coverbench
/// conformance` (the report card, cli/conformance_command.cpp) and the C++ suite
/// (tests/experiments/conformance_test.cpp) both use these, so a planner passes both or neither.

#include <functional>
#include <string>
#include <vector>

#include "coverbench/experiment.hpp"
#include "coverbench/planner.hpp"
#include "coverbench/wall.hpp"

namespace coverbench {

/// The conformance wall folders under a source tree: datasets/canonical and datasets/conformance.
std::vector<std::string> conformanceWallFolders(const std::string& source_dir);
/// Every wall file (*.json) of the folders, sorted by path. Throws InputError naming a folder that
/// is not one or a list of folders that holds no wall file.
std::vector<std::string> wallFilesIn(const std::vector<std::string>& folders);
/// The two tools every wall is checked at: s = 0.1 m with c = 0.02 m, and s = 0.05 m with c = 0.
std::vector<ToolParams> conformanceTools();

/// Each wall file of `files` (loaded once) at each of conformanceTools(): `visit(file, problem)`,
/// `planner`'s problem holding the wall, the tool and `params` (the one loop of the card and the
/// suites).
void forEachConformanceProblem(const PlannerInfo& planner, const std::vector<std::string>& files, const Params& params,
                               const std::function<void(const std::string& file, Problem& problem)>& visit);

/// What a correct planner must do on a wall at a tool with the default (holonomic) vehicle,
/// decided by the free centre region F the planners' toolkit computes (freeRegion with its
/// margin), not by any planner's account:
/// - F empty (the tool fits nowhere): `no_reachable_area` with a reason, no path;
/// - F in several pieces: `partial` with a reason saying what was left out (a path never leaves
///   F, so it reaches one piece);
/// - F one piece: `ok`, everything reachable covered.
/// `invalid_input` is expected nowhere: every wall file that loads is a valid input.
struct ExpectedOutcome {
  PlanStatus status = PlanStatus::Ok;
  std::size_t free_components = 0;  ///< F's pieces at this tool
  std::string why;                  ///< "F is one piece", "F is in 2 pieces", "F is empty: the tool fits nowhere"
};
ExpectedOutcome expectedOutcome(const Wall& wall, const ToolParams& tool);

/// One judged plan (planAndJudge) against the wall's expected outcome. `cause` is empty when the
/// planner did what a correct planner must: the expected status (a failure status such as crash,
/// timeout, memory_limit, error, invalid_output or metrics_error never is), a reason with
/// `partial` and every status but `ok`, a valid path, and with default parameters an `ok` path
/// covering at least `min_coverage_reachable` (the planner's declared promise; it applies where
/// F is one piece). Otherwise `cause` names the status, the planner's reason and what was expected,
/// on one line.
struct ConformanceCheck {
  std::string cause;
  bool outcome = false;  ///< the status, reason and path the wall calls for (the promise aside)
  bool promise_applies = false;  ///< ok where F is one piece, default parameters
  bool promise_kept = true;
  double coverage_reachable = 0.0;  ///< of the path (NaN without one)
  bool passed() const { return cause.empty(); }
};
ConformanceCheck checkConformance(const ExpectedOutcome& expected, const JudgedPlan& judged,
                                  double min_coverage_reachable, bool default_params);

}  // namespace coverbench
