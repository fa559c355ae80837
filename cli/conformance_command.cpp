// `coverbench conformance PLANNER`: the conformance checks the test suite applies to every
// registered planner, for any planner (in-tree or external), as a report card.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "commands.hpp"
#include "coverbench/experiment.hpp"
#include "coverbench/external_planner.hpp"
#include "coverbench/files.hpp"
#include "coverbench/free_region.hpp"
#include "coverbench/metrics.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/wall_file.hpp"
#include "coverbench/workspace.hpp"

namespace coverbench::cli {
namespace {

namespace fs = std::filesystem;

/// One wall at one tool: what the planner did and which checks it passed.
struct CardRow {
  std::string wall, file;
  ToolParams tool;
  std::string status, reason;
  bool contract = false;       ///< a valid path, or no path and a reason; never `error`
  bool valid = false;          ///< the path passes the metrics engine's exact validity check
  bool deterministic = false;  ///< a second plan gave the same path, bit for bit
  double coverage = NAN;       ///< coverage_reachable, when there is a path
  bool promise_applies = false;  ///< ok, one free component, default parameters
  bool promise_kept = true;
  double plan_ms = 0.0;        ///< the first plan's wall-clock time (measured)
  bool passed() const { return contract && deterministic && promise_kept; }  // contract holds `valid` for a path
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

std::vector<std::string> wallFiles(const std::vector<std::string>& folders) {
  std::vector<std::string> files;
  for (const std::string& dir : folders) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) throw InputError(dir, "(folder)", "is not a folder of wall files");
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().extension() == ".json") files.push_back(e.path().string());
  }
  std::sort(files.begin(), files.end());
  if (files.empty()) throw InputError(folders.front(), "(folder)", "holds no wall file (*.json)");
  return files;
}

}  // namespace

int conformanceCommand(const ConformanceOptions& o) {
  const PlannerInfo& info = external::plannerNamed(o.planner, "PLANNER");
  const std::vector<std::pair<std::string, std::string>> settings = splitSettings(o.params);
  const Params params = resolveParams(info, settings);
  std::vector<std::string> folders = o.walls;
  if (folders.empty()) folders = {o.source_dir + "/datasets/canonical", o.source_dir + "/datasets/conformance"};
  std::vector<CardRow> rows;
  for (const std::string& file : wallFiles(folders))
    for (const ToolParams& tool : {ToolParams{0.1, 0.02}, ToolParams{0.05, 0.0}}) {
      const Wall wall = loadWallFile(file);
      Problem problem;
      problem.wall = &wall;
      problem.tool = tool;
      problem.params = params;
      CardRow row;
      row.wall = wall.name;
      row.file = fs::path(file).filename().string();
      row.tool = tool;
      // An external planner's processes are held to the experiments' default memory limit.
      problem.memory_limit_bytes = external::kDefaultMemoryLimitBytes;
      // Judged as `plan` and a run judge it: a path beyond the scoring limits fails its row with
      // the reason (the card goes on).
      const JudgedPlan judged = planAndJudge(info, problem, Budget(std::chrono::duration<double>(o.time_limit_s)));
      const PlanResult& a = judged.result;
      const PlanResult b = runPlanner(info, problem, Budget(std::chrono::duration<double>(o.time_limit_s)));
      row.status = toString(a.status);
      row.reason = a.reason;
      row.plan_ms = a.plan_time_ms;
      row.deterministic = a.status == b.status && a.path.waypoints.size() == b.path.waypoints.size() &&
                          a.path.tool_on == b.path.tool_on && a.path.bulge == b.path.bulge;
      for (std::size_t i = 0; row.deterministic && i < a.path.waypoints.size(); ++i)
        row.deterministic = a.path.waypoints[i].x == b.path.waypoints[i].x && a.path.waypoints[i].y == b.path.waypoints[i].y;
      if (a.hasPath() && !judged.not_scored.empty()) {
        row.status = toString(judged.verdict);  // metrics_error: the row fails, saying why
        row.reason = judged.reason;
        row.contract = false;
      } else if (a.hasPath()) {
        const PathMetrics& m = judged.metrics;
        row.valid = m.validity.valid;
        row.coverage = m.coverage.coverage_reachable;
        row.contract = row.valid && (a.status == PlanStatus::Ok || !a.reason.empty());
        // The promise is for walls whose free region is one piece (counted here, not taken from the
        // planner's own account, which an external planner need not give).
        row.promise_applies =
            settings.empty() && a.status == PlanStatus::Ok && componentsByArea(freeRegion(wall, tool)).size() <= 1;
        row.promise_kept = !row.promise_applies || row.coverage >= info.min_coverage_reachable;
      } else {
        row.contract = a.status != PlanStatus::Error && !a.reason.empty() && a.path.waypoints.empty();
      }
      rows.push_back(std::move(row));
    }

  std::size_t passed = 0;
  for (const CardRow& r : rows) passed += r.passed();
  std::string text;
  if (o.format == "json") {
    nlohmann::ordered_json j;
    j["planner"] = info.name;
    j["version"] = info.version;
    j["params"] = nlohmann::ordered_json::object();
    for (const auto& [k, v] : params.all()) std::visit([&, name = k](const auto& x) { j["params"][name] = x; }, v);
    j["promise_min_coverage_reachable"] = info.min_coverage_reachable;
    j["walls"] = nlohmann::ordered_json::array();
    for (const CardRow& r : rows)
      j["walls"].push_back({{"wall", r.wall}, {"file", r.file}, {"tool_width", r.tool.tool_width},
                            {"clearance", r.tool.clearance}, {"status", r.status}, {"reason", r.reason},
                            {"contract", r.contract}, {"valid", r.valid}, {"deterministic", r.deterministic},
                            {"coverage_reachable", std::isfinite(r.coverage) ? nlohmann::ordered_json(r.coverage) : nullptr},
                            {"promise_applies", r.promise_applies}, {"promise_kept", r.promise_kept},
                            {"plan_time_ms", r.plan_ms}, {"passed", r.passed()}});
    j["passed"] = passed;
    j["checked"] = rows.size();
    text = j.dump(1) + "\n";
  } else {
    std::string p;
    for (const auto& [k, v] : params.all()) p += (p.empty() ? "" : ", ") + k + "=" + toString(v);
    text = "# Conformance: " + info.name + " (version " + info.version + ")\n\n";
    text += "Parameters: " + (p.empty() ? std::string("none") : p) + ". Promise: coverage_reachable >= " +
            fixed(info.min_coverage_reachable, 3) +
            " with default parameters on every wall whose free region is connected.\n\n"
            "Each wall is planned twice at each tool (s = tool width, c = clearance, metres). A row passes when the "
            "planner returns a path the metrics engine finds valid, or no path with a reason (never `error`); the "
            "second plan is the same path bit for bit; and an `ok` path keeps the promise where it applies. "
            "Plan time is the first plan's wall-clock time on this machine (measured, not checked).\n\n";
    text += "| wall | s | c | status | valid | same path twice | coverage_reachable | promise | plan ms | passed |\n";
    text += "|---|---|---|---|---|---|---|---|---|---|\n";
    for (const CardRow& r : rows)
      text += "| " + cell(r.wall) + " | " + shortNumber(r.tool.tool_width) + " | " + shortNumber(r.tool.clearance) + " | " +
              r.status + (r.reason.empty() ? "" : " (" + cell(r.reason) + ")") + " | " +
              (r.hasPathStatus() ? (r.valid ? "yes" : "**no**") : "-") + " | " + (r.deterministic ? "yes" : "**no**") +
              " | " + fixed(r.coverage, 4) + " | " +
              (r.promise_applies ? (r.promise_kept ? "kept" : "**broken**") : "-") + " | " + fixed(r.plan_ms, 1) +
              " | " + (r.passed() ? "yes" : "**no**") + " |\n";
    text += "\n" + std::to_string(passed) + " of " + std::to_string(rows.size()) + " passed.\n";
  }
  if (o.out.empty()) {
    std::fwrite(text.data(), 1, text.size(), stdout);
  } else {
    OutputFiles files;
    files.add(o.out, text);
    files.commit();
  }
  std::fprintf(stderr, "%s: %zu of %zu passed\n", info.name.c_str(), passed, rows.size());
  return passed == rows.size() ? 0 : 1;
}

}  // namespace coverbench::cli
