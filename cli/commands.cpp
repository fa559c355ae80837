#include "commands.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "coverbench/metrics.hpp"
#include "coverbench/plan_file.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/svg.hpp"
#include "coverbench/workspace.hpp"

namespace coverbench::cli {
namespace {

namespace fs = std::filesystem;

std::string typeName(ParamType t) {
  switch (t) {
    case ParamType::Number: return "number";
    case ParamType::Integer: return "integer";
    case ParamType::Bool: return "bool";
    case ParamType::Choice: return "choice";
  }
  return "?";
}

std::vector<std::pair<std::string, std::string>> splitSettings(const std::vector<std::string>& items) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const std::string& item : items) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0) throw InputError("--param", item, "expected key=value");
    out.emplace_back(item.substr(0, eq), item.substr(eq + 1));
  }
  return out;
}

struct Outcome {
  PlanFile plan;
  std::string plan_json;
  std::string svg;
};

/// Plans one wall with one planner and renders its outputs (nothing is written here).
Outcome planOnce(const Wall& wall, const PlannerInfo& planner, const ToolParams& tool, Params params,
                 double time_limit_s) {
  Problem problem;
  problem.wall = &wall;
  problem.tool = tool;
  problem.params = params;
  Outcome o;
  o.plan.planner = planner.name;
  o.plan.wall = wall.name;
  o.plan.tool = tool;
  o.plan.params = std::move(params);
  o.plan.result = runPlanner(planner, problem, Budget(std::chrono::duration<double>(time_limit_s)));
  o.plan.validity = checkValidity(wall, tool, o.plan.result.path);
  o.plan_json = planFileJson(o.plan);
  const Region free = freeRegion(wall, tool);
  SvgContent content;
  content.wall = &wall;
  content.tool = tool;
  content.free = &free;
  content.path = &o.plan.result.path;
  char title[256];
  std::snprintf(title, sizeof title, "%s / %s  (s = %g m, c = %g m)  %s%s", wall.name.c_str(), planner.name.c_str(),
                tool.tool_width, tool.clearance, toString(o.plan.result.status).c_str(),
                o.plan.result.status == PlanStatus::Ok ? (o.plan.validity.valid ? ", valid" : ", INVALID") : "");
  content.title = title;
  o.svg = renderSvg(content);
  return o;
}

bool succeeded(const PlanFile& plan) { return plan.result.status == PlanStatus::Ok && plan.validity.valid; }

}  // namespace

void listPlanners(std::ostream& out) {
  for (const PlannerInfo& p : registeredPlanners()) {
    out << p.name << ": " << p.summary << "\n";
    out << "  reference: " << p.reference << "\n";
    for (const ParamSpec& s : p.params) {
      out << "  --param " << s.name << "=<" << typeName(s.type) << ">  default " << toString(s.default_value);
      if (s.type == ParamType::Number || s.type == ParamType::Integer)
        out << ", range [" << toString(s.min) << ", " << toString(s.max) << "]";
      if (!s.unit.empty()) out << " " << s.unit;
      out << "  " << s.description << "\n";
    }
  }
}

int planCommand(const PlanOptions& options) {
  validateTool(options.tool, "command line");
  if (!(options.time_limit_s > 0.0)) throw InputError("--time-limit", "time_limit", "must be positive");
  const Wall wall = loadWallFile(options.wall);
  const PlannerInfo& planner = findPlanner(options.planner);
  Params params = resolveParams(planner, splitSettings(options.params));
  const Outcome o = planOnce(wall, planner, options.tool, std::move(params), options.time_limit_s);
  writeFileAtomically(options.out, o.plan_json);
  if (!options.svg.empty()) writeFileAtomically(options.svg, o.svg);
  const PlanResult& r = o.plan.result;
  std::cout << planner.name << " on " << wall.name << ": " << toString(r.status)
            << (r.reason.empty() ? "" : " (" + r.reason + ")") << ", " << r.path.waypoints.size() << " waypoints, "
            << (o.plan.validity.valid ? "valid" : "INVALID: " + std::to_string(o.plan.validity.violations) +
                                                      " violating segments")
            << ", " << r.plan_time_ms << " ms\n";
  return succeeded(o.plan) ? 0 : 3;
}

int showcaseCommand(const ShowcaseOptions& options) {
  validateTool(options.tool, "command line");
  if (!fs::is_directory(options.walls)) throw InputError(options.walls, "--walls", "is not a folder");
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(options.walls))
    if (entry.path().extension() == ".json") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  if (files.empty()) throw InputError(options.walls, "--walls", "contains no .json wall files");
  std::vector<Wall> walls;
  for (const fs::path& f : files) walls.push_back(loadWallFile(f.string()));  // all input checked first

  const fs::path out = options.out;
  fs::create_directories(out / "plans");
  std::string table =
      "| wall | planner | status | valid | violations | min clearance (m) | waypoints | length (m) | transit (m) | "
      "plan time (ms) |\n|---|---|---|---|---|---|---|---|---|---|\n";
  std::string csv = "wall,planner,status,valid,violations,min_clearance_m,waypoints,length_m,transit_m,plan_time_ms\n";
  std::string html_rows, gallery;
  int exit_code = 0;
  for (const Wall& wall : walls) {
    for (const PlannerInfo& planner : registeredPlanners()) {
      const Outcome o = planOnce(wall, planner, options.tool, resolveParams(planner, {}), 60.0);
      const std::string stem = wall.name + "__" + planner.name;
      writeFileAtomically((out / "plans" / (stem + ".json")).string(), o.plan_json);
      writeFileAtomically((out / "plans" / (stem + ".svg")).string(), o.svg);
      const Lengths l = pathLengths(o.plan.result.path);
      char row[512];
      const double mc = o.plan.validity.min_clearance;
      std::snprintf(row, sizeof row, "%s | %s | %s | %s | %zu | %s | %zu | %.2f | %.2f | %.2f", wall.name.c_str(),
                    planner.name.c_str(), toString(o.plan.result.status).c_str(),
                    o.plan.validity.valid ? "yes" : "NO", o.plan.validity.violations,
                    std::isfinite(mc) ? toString(mc).c_str() : "-", o.plan.result.path.waypoints.size(), l.total,
                    l.transit, o.plan.result.plan_time_ms);
      std::string line = row;
      table += "| " + line + " |\n";
      std::string cells = line;
      for (std::size_t pos; (pos = cells.find(" | ")) != std::string::npos;) cells.replace(pos, 3, "</td><td>");
      html_rows += "<tr><td>" + cells + "</td></tr>\n";
      gallery += "<figure><img src=\"plans/" + stem + ".svg\" alt=\"" + stem + "\"><figcaption><a href=\"plans/" + stem +
                 ".json\">" + stem + ".json</a></figcaption></figure>\n";
      for (char& ch : line)
        if (ch == '|') ch = ',';
      line.erase(std::remove(line.begin(), line.end(), ' '), line.end());
      csv += line + "\n";
      if (!succeeded(o.plan)) exit_code = 3;
      std::cout << "  " << stem << ": " << toString(o.plan.result.status)
                << (o.plan.validity.valid ? ", valid" : ", INVALID") << "\n";
    }
  }
  writeFileAtomically((out / "summary.md").string(),
                      "# CoverBench showcase\n\nTool width " + toString(options.tool.tool_width) + " m, clearance " +
                          toString(options.tool.clearance) +
                          " m, default planner parameters. Pictures and plan files are in `plans/`.\n\n" + table);
  writeFileAtomically((out / "summary.csv").string(), csv);
  writeFileAtomically(
      (out / "index.html").string(),
      "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>CoverBench showcase</title><style>"
      "body{font-family:sans-serif;margin:2em}table{border-collapse:collapse}td,th{border:1px solid #ccc;"
      "padding:2px 8px;text-align:right}td:first-child,td:nth-child(2){text-align:left}"
      "figure{display:inline-block;margin:1em;vertical-align:top}img{max-width:760px}</style></head><body>\n"
      "<h1>CoverBench showcase</h1>\n<p>Tool width " + toString(options.tool.tool_width) + " m, clearance " +
          toString(options.tool.clearance) +
          " m, default planner parameters. Every path is validated exactly.</p>\n<table>\n<tr><th>wall</th>"
          "<th>planner</th><th>status</th><th>valid</th><th>violations</th><th>min clearance (m)</th>"
          "<th>waypoints</th><th>length (m)</th><th>transit (m)</th><th>plan time (ms)</th></tr>\n" +
          html_rows + "</table>\n" + gallery + "</body></html>\n");
  std::cout << "summary table: " << (out / "summary.md").string() << "\nreport: " << (out / "index.html").string()
            << "\n";
  return exit_code;
}

}  // namespace coverbench::cli
