#pragma once
/// Running one planner on one problem, the one way every entrance runs it (a run, `coverbench
/// plan`, `conformance`, Python, the server): under the budget, every exception caught, the wall's
/// start and end attached, and for a car the one decision of who drives it (the planner itself,
/// or the runner smoothing a path planned for a tool that turns on the spot).
#include <string>

#include "coverbench/metrics.hpp"
#include "coverbench/planner.hpp"
#include "coverbench/run_record.hpp"

namespace coverbench {

/// Runs one planner on one problem, catching every exception at this boundary and turning it
/// into an Error status; fills `plan_time_ms` with the wall-clock time of the call. For a car, a
/// planner that plans for cars (PlannerInfo::plans_for_car) is given the car unless its `car_plan`
/// is `smoothed`; every other plan is made for a tool that turns on the spot and smoothed here.
/// An in-tree planner that plans for disks (not PlannerInfo::plans_line_tool) is given a
/// rectangle tool's circumscribed disk (circumscribedDisk) in its place.
PlanResult runPlanner(const PlannerInfo& planner, const Problem& problem, const Budget& budget);

/// A planner's status as a run's (a run adds what only an execution can end in).
RunStatus runStatusOf(PlanStatus status);

/// One plan judged the one way every command judges a plan (`coverbench plan`, `conformance`,
/// Python's coverbench.plan; a run's record says the same): the planner's result, the metrics
/// engine's score of its path (with its validity), and the verdict, the status a run would store:
/// the planner's status, or invalid_output for a path that fails the validity check, or
/// metrics_error for a path beyond the scoring limits (then `not_scored` says why).
struct JudgedPlan {
  PlanResult result;
  PathMetrics metrics;
  std::string not_scored;
  RunStatus verdict = RunStatus::Error;
  std::string reason;  ///< the verdict's reason
  bool succeeded() const { return verdict == RunStatus::Ok; }
};
JudgedPlan planAndJudge(const PlannerInfo& planner, const Problem& problem, const Budget& budget);
/// What a line or rectangle tool's run says of its plan: "" for a disk or when the planner plans
/// for the tool's shape (PlannerInfo::plans_line_tool) or planned this `result` for it
/// (PlanResult::planned_for_shape), else, of a path or of no_reachable_area, that it planned for
/// the shape's circumscribed disk (an external planner: what it was sent).
std::string toolShapeNote(const PlannerInfo& planner, const ToolParams& tool, const PlanResult& result);


}  // namespace coverbench
