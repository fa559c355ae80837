#include "coverbench/conformance.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "coverbench/files.hpp"
#include "coverbench/problem_builder.hpp"
#include "coverbench/wall_file.hpp"
#include "coverbench/free_region.hpp"
#include "coverbench/workspace.hpp"

namespace coverbench {

namespace fs = std::filesystem;

std::vector<std::string> conformanceWallFolders(const std::string& source_dir) {
  return {source_dir + "/datasets/canonical", source_dir + "/datasets/conformance"};
}

std::vector<std::string> wallFilesIn(const std::vector<std::string>& folders) {
  std::vector<std::string> files;
  for (const std::string& dir : folders) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) throw InputError(dir, "(folder)", "is not a folder of wall files");
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().extension() == ".json") files.push_back(e.path().string());
  }
  std::sort(files.begin(), files.end());
  if (files.empty()) throw InputError(folders.empty() ? std::string("(no folder)") : folders.front(), "(folder)",
                                      "holds no wall file (*.json)");
  return files;
}

std::vector<ToolParams> conformanceTools() { return {ToolParams{0.1, 0.02}, ToolParams{0.05, 0.0}}; }

ExpectedOutcome expectedOutcome(const Wall& wall, const ToolParams& tool) {
  ExpectedOutcome e;
  e.free_components = componentsByArea(freeRegion(wall, tool)).size();
  if (e.free_components == 0) {
    e.status = PlanStatus::NoReachableArea;
    e.why = "F is empty: the tool fits nowhere";
  } else if (e.free_components == 1) {
    e.status = PlanStatus::Ok;
    e.why = "F is one piece";
  } else {
    e.status = PlanStatus::Partial;
    e.why = "F is in " + std::to_string(e.free_components) + " pieces";
  }
  return e;
}

namespace {

std::string fixed4(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.4f", v);
  return buf;
}

/// "status (reason)", or the status alone.
std::string said(RunStatus status, const std::string& reason) {
  return std::string(toString(status)) + (reason.empty() ? "" : " (" + reason + ")");
}

}  // namespace

ConformanceCheck checkConformance(const ExpectedOutcome& expected, const JudgedPlan& judged,
                                  double min_coverage_reachable, bool default_params) {
  ConformanceCheck c;
  const PlanResult& r = judged.result;
  const RunStatus got = judged.verdict;
  c.coverage_reachable = r.hasPath() && judged.not_scored.empty() ? judged.metrics.coverage.coverage_reachable : NAN;
  const std::string want = toString(expected.status) + " expected: " + expected.why;
  switch (got) {
    case RunStatus::Crash:
    case RunStatus::Timeout:
    case RunStatus::MemoryLimit:
    case RunStatus::Error:
    case RunStatus::InvalidOutput:
    case RunStatus::MetricsError:
      c.cause = said(got, judged.reason) + "; " + want;
      return c;
    default:
      break;
  }
  if (got != RunStatus::Ok && judged.reason.empty()) {
    c.cause = std::string(toString(got)) + " without a reason; " + want;
    return c;
  }
  if (r.status != expected.status) {
    c.cause = said(got, judged.reason) + "; " + want;
    return c;
  }
  if (!r.hasPath() && !r.path.waypoints.empty()) {
    c.cause = std::string(toString(got)) + " with a path (a failure status has none)";
    return c;
  }
  c.outcome = true;
  c.promise_applies = default_params && r.status == PlanStatus::Ok && expected.free_components == 1;
  if (c.promise_applies && !(c.coverage_reachable >= min_coverage_reachable)) {
    c.promise_kept = false;
    c.cause = "ok at coverage_reachable " + fixed4(c.coverage_reachable) + ", below the declared " +
              fixed4(min_coverage_reachable);
  }
  return c;
}

void forEachConformanceProblem(const PlannerInfo& planner, const std::vector<std::string>& files, const Params& params,
                               const std::function<void(const std::string& file, Problem& problem)>& visit) {
  for (const std::string& file : files) {
    const Wall wall = loadWallFile(file);
    for (const ToolParams& tool : conformanceTools()) {
      ProblemInputs inputs;
      inputs.wall = &wall;
      inputs.tool = tool;
      inputs.params = params;
      Problem problem = buildProblem(planner, std::move(inputs), file);
      visit(file, problem);
    }
  }
}

}  // namespace coverbench
