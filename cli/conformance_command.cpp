// `coverbench conformance PLANNER`: the conformance checks the test suite applies to every
// registered planner, for any planner (in-tree or external), as a report card.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>


#include "commands.hpp"
#include "coverbench/conformance.hpp"
#include "coverbench/experiment.hpp"
#include "coverbench/external_planner.hpp"
#include "coverbench/files.hpp"
#include "coverbench/metrics.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/run_planner.hpp"
#include "coverbench/wall_file.hpp"

namespace coverbench::cli {
namespace {

namespace fs = std::filesystem;

/// One wall at one tool: what the planner did, what a correct planner must do there
/// (coverbench/conformance.hpp) and, for a failed row, why it failed.
struct CardRow {
  std::string wall, file;
  ToolParams tool;
  std::string expected;  ///< the status the wall calls for
  std::string status, reason;
  std::string cause;           ///< why the row failed ("" when it passed)
  bool contract = false;       ///< the outcome the wall calls for: its status, a reason where one is due, a valid path
  bool valid = false;          ///< the path passes the metrics engine's exact validity check
  bool checked_twice = false;  ///< planned a second time (only a row that passed so far is)
  bool deterministic = false;  ///< that second plan gave the same path, bit for bit
  double coverage = NAN;       ///< coverage_reachable, when there is a path
  bool promise_applies = false;  ///< ok where F is one piece, default parameters
  bool promise_kept = true;
  double plan_ms = 0.0;        ///< the first plan's wall-clock time (measured)
  bool passed() const { return cause.empty(); }
  bool hasPathStatus() const { return status == "ok" || status == "partial"; }
};

std::string fixed(double v, int digits) {
  if (!std::isfinite(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

/// Text in a Markdown table cell: pipes escaped, on one line.
std::string cell(std::string s) {
  std::string out;
  for (char c : s) out += c == '|' ? std::string("\\|") : c == '\n' || c == '\r' ? std::string(" ") : std::string(1, c);
  return out;
}

/// The most of an external planner's stderr a row's reason quotes: its last bytes, from a line's start.
constexpr std::size_t kStderrTailBytes = 2048;

/// The end of what a failed plan's processes wrote to stderr (PlanResult::stderr_tail, kept by the
/// external-planner host), as a row's reason quotes it: its last kStderrTailBytes, from a line's
/// start, trimmed of surrounding blank space.
std::string quotedStderr(std::string text) {
  if (text.size() > kStderrTailBytes) {
    text = text.substr(text.size() - kStderrTailBytes);
    const std::size_t nl = text.find('\n');
    if (nl != std::string::npos && nl + 1 < text.size()) text = "..." + text.substr(nl + 1);
  }
  const std::size_t from = text.find_first_not_of(" \t\r\n"), to = text.find_last_not_of(" \t\r\n");
  return from == std::string::npos ? std::string() : text.substr(from, to - from + 1);
}

bool samePath(const PlanResult& a, const PlanResult& b) {
  if (a.status != b.status || a.path.waypoints.size() != b.path.waypoints.size() || a.path.tool_on != b.path.tool_on ||
      a.path.bulge != b.path.bulge)
    return false;
  for (std::size_t i = 0; i < a.path.waypoints.size(); ++i)
    if (a.path.waypoints[i].x != b.path.waypoints[i].x || a.path.waypoints[i].y != b.path.waypoints[i].y) return false;
  return true;
}

}  // namespace

int conformanceCommand(const ConformanceOptions& o) {
  const PlannerInfo& info = external::plannerNamed(o.planner, "PLANNER");
  const std::vector<std::pair<std::string, std::string>> settings = splitSettings(o.params);
  const Params params = resolveParams(info, settings);
  const std::vector<std::string> files = wallFilesIn(o.walls.empty() ? conformanceWallFolders(o.source_dir) : o.walls);
  std::vector<CardRow> rows;
  forEachConformanceProblem(info, files, params, [&](const std::string& file, Problem& problem) {
    const Wall& wall = *problem.wall;
    const ToolParams& tool = problem.tool;
    // An external planner's processes are held to the experiments' default memory limit.
    problem.memory_limit_bytes = external::kDefaultMemoryLimitBytes;
    const ExpectedOutcome expected = expectedOutcome(wall, tool);
    CardRow row;
    row.wall = wall.name;
    row.file = fs::path(file).filename().string();
    row.tool = tool;
    row.expected = toString(expected.status);
    // Judged as `plan` and a run judge it: an invalid path is invalid_output, a path beyond
    // the scoring limits metrics_error, each with its reason (the card goes on).
    JudgedPlan judged = planAndJudge(info, problem, Budget(std::chrono::duration<double>(o.time_limit_s)));
    const PlanResult& a = judged.result;
    const std::string tail = quotedStderr(a.stderr_tail);
    // A planner that failed says why on its stderr (an import error, a traceback): its reason quotes the end.
    const bool failed = judged.verdict == RunStatus::Crash || judged.verdict == RunStatus::Error ||
                        judged.verdict == RunStatus::InvalidOutput || judged.verdict == RunStatus::Timeout ||
                        judged.verdict == RunStatus::MemoryLimit;
    if (failed && !tail.empty() && judged.reason.find(tail) == std::string::npos)
      judged.reason += (judged.reason.empty() ? "" : "; ") + std::string("the planner's stderr ended: ") + tail;
    const ConformanceCheck check = checkConformance(expected, judged, info.min_coverage_reachable, settings.empty());
    row.status = toString(judged.verdict);
    row.reason = judged.reason;
    row.plan_ms = a.plan_time_ms;
    row.valid = a.hasPath() && judged.not_scored.empty() && judged.metrics.validity.valid;
    row.coverage = check.coverage_reachable;
    row.contract = check.outcome;
    row.promise_applies = check.promise_applies;
    row.promise_kept = check.promise_kept;
    row.cause = check.cause;
    if (check.passed()) {  // the same problem again: the same path, bit for bit
      const PlanResult b = runPlanner(info, problem, Budget(std::chrono::duration<double>(o.time_limit_s)));
      row.checked_twice = true;
      row.deterministic = samePath(a, b);
      if (!row.deterministic)
        row.cause = "a second plan gave " + (b.status == a.status ? std::string("a different path")
                                                                  : toString(b.status) + " (" + b.reason + ")");
    }
    rows.push_back(std::move(row));
  });

  std::size_t passed = 0;
  for (const CardRow& r : rows) passed += r.passed();
  std::string text;
  if (o.format == "json") {
    nlohmann::ordered_json j;
    j["planner"] = info.name;
    j["version"] = info.version;
    j["params"] = paramsJson(params);
    j["promise_min_coverage_reachable"] = info.min_coverage_reachable;
    j["walls"] = nlohmann::ordered_json::array();
    for (const CardRow& r : rows)
      j["walls"].push_back({{"wall", r.wall}, {"file", r.file}, {"tool_width", r.tool.tool_width},
                            {"clearance", r.tool.clearance}, {"expected", r.expected}, {"status", r.status},
                            {"reason", r.reason}, {"contract", r.contract}, {"valid", r.valid},
                            {"deterministic", r.checked_twice ? nlohmann::ordered_json(r.deterministic) : nullptr},
                            {"coverage_reachable", std::isfinite(r.coverage) ? nlohmann::ordered_json(r.coverage) : nullptr},
                            {"promise_applies", r.promise_applies}, {"promise_kept", r.promise_kept},
                            {"plan_time_ms", r.plan_ms}, {"passed", r.passed()}, {"cause", r.cause}});
    j["passed"] = passed;
    j["checked"] = rows.size();
    text = j.dump(1, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
  } else {
    const std::string p = paramsList(params);
    text = "# Conformance: " + info.name + " (version " + info.version + ")\n\n";
    text += "Parameters: " + (p.empty() ? std::string("none") : p) + ". Promise: coverage_reachable >= " +
            fixed(info.min_coverage_reachable, 3) +
            " with default parameters on every wall whose free region is connected.\n\n"
            "Each wall is planned at two tools (s = tool width, c = clearance, metres). A row passes when the planner "
            "does what a correct planner must there (docs/ADDING_A_PLANNER.md, the contract): where the tool's centre "
            "region F is one piece, a valid `ok` path; where F is in several pieces, a valid `partial` path with its "
            "reason; where F is empty, `no_reachable_area` with its reason. `crash`, `timeout`, `memory_limit`, "
            "`error`, `invalid_output` (an invalid path) and `metrics_error` fail. An `ok` path keeps the promise where "
            "it applies, and a second plan gives the same path bit for bit. `ok` means no reachable part left out, not "
            "100 % of the reachable area R: a round tool's finite path leaves slivers at the ends of rows and in F's "
            "corners, and the promise is the least coverage_reachable the planner claims (docs/run_lifecycle.md, "
            "\"What ok leaves\"). "
            "Plan time is the first plan's wall-clock time on this machine (measured, not checked).\n\n";
    text += "| wall | s | c | expected | status | valid | same path twice | coverage_reachable | promise | plan ms | passed |\n";
    text += "|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const CardRow& r : rows)
      text += "| " + cell(r.wall) + " | " + shortNumber(r.tool.tool_width) + " | " + shortNumber(r.tool.clearance) +
              " | " + r.expected + " | " + r.status + (r.reason.empty() ? "" : " (" + cell(r.reason) + ")") + " | " +
              (r.hasPathStatus() ? (r.valid ? "yes" : "**no**") : "-") + " | " +
              (r.checked_twice ? (r.deterministic ? "yes" : "**no**") : "-") + " | " + fixed(r.coverage, 4) + " | " +
              (r.promise_applies ? (r.promise_kept ? "kept" : "**broken**") : "-") + " | " + fixed(r.plan_ms, 1) +
              " | " + (r.passed() ? "yes" : "**no**") + " |\n";
    text += "\n" + std::to_string(passed) + " of " + std::to_string(rows.size()) + " passed.\n";
    if (passed < rows.size()) {
      text += "\n## Failed rows\n\n";
      for (const CardRow& r : rows)
        if (!r.passed())
          text += "- " + cell(r.wall) + " (" + r.file + ", " + toolLabel(r.tool) + "): " + cell(r.cause) + "\n";
    }
  }
  if (o.out.empty()) {
    std::fwrite(text.data(), 1, text.size(), stdout);
  } else {
    OutputFiles files_out;
    files_out.add(o.out, text);
    files_out.commit();
  }
  std::fprintf(stderr, "%s: %zu of %zu passed\n", info.name.c_str(), passed, rows.size());
  return passed == rows.size() ? 0 : 1;
}

}  // namespace coverbench::cli
