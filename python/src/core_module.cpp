// coverbench._core: CoverBench's C++ from Python (pybind11, one translation unit). Walls are
// passed as wall-file JSON text and results come back as JSON text: the Python package
// (python/coverbench/__init__.py) turns them into dicts, so this module holds no Python types of
// its own and every input is checked by the same parsers as the command line.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <nlohmann/json.hpp>

#include "coverbench/experiment.hpp"
#include "coverbench/external_planner.hpp"
#include "coverbench/judge.hpp"
#include "coverbench/json_input.hpp"
#include "coverbench/limits.hpp"
#include "coverbench/metrics.hpp"
#include "coverbench/plan_file.hpp"
#include "coverbench/records.hpp"
#include "coverbench/problem_builder.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/run_planner.hpp"
#include "coverbench/results_db.hpp"
#include "coverbench/wall_file.hpp"

namespace py = pybind11;
using nlohmann::ordered_json;

namespace coverbench {
namespace {

ordered_json number(double v) { return std::isfinite(v) ? ordered_json(v) : ordered_json(nullptr); }

/// The validity check's answer as plan() and score() give it: `valid` a bool, `violations` the
/// number of violating segments, `violating_segments` the first of them (segment i joins
/// waypoints i and i+1). The one place that turns a Validity into Python's dict: details added
/// to Validity (the points of each violating segment, what it violates) go here, for both.
/// valid as a bool, the count, the first violating segments' indices, and what the first of them
/// hit (`violation_details`: points, the obstacle by index and label or the wall's edge, the gap
/// reached; the same list a plan file and a run carry) with `invalid_reason`, the run's message.
ordered_json validityJson(const Validity& v, double clearance) {
  return {{"valid", v.valid},
          {"violations", v.violations},
          {"violating_segments", v.violating},
          {"violation_details", ordered_json::parse(violationsJson(v))},
          {"invalid_reason", v.valid ? std::string() : describeViolations(v, clearance)}};
}

/// A wall from wall-file text, checked as the command line checks it.
Wall wallOf(const std::string& text, const std::string& source) { return parseWallJson(text, source); }

std::string planners() {
  ordered_json out = ordered_json::array();
  for (const PlannerInfo& p : registeredPlanners()) {
    ordered_json params = ordered_json::array();
    for (const ParamSpec& s : p.params) params.push_back(paramSpecJson(s));
    out.push_back({{"name", p.name}, {"version", p.version}, {"summary", p.summary}, {"reference", p.reference},
                   {"params", params}, {"min_coverage_reachable", p.min_coverage_reachable}});
  }
  return out.dump();
}

Path pathOf(const std::vector<std::pair<double, double>>& waypoints, const std::vector<bool>& tool_on,
            const std::vector<double>& bulge) {
  if (waypoints.empty()) throw InputError("waypoints", "waypoints", "must hold at least one point");
  if (tool_on.size() + 1 != waypoints.size())
    throw InputError("tool_on", "tool_on", "must hold one value per segment (" + std::to_string(waypoints.size() - 1) + ")");
  if (!bulge.empty() && bulge.size() != tool_on.size())
    throw InputError("bulge", "bulge", "must be empty or hold one value per segment");
  Path p;
  for (const auto& [x, y] : waypoints) p.waypoints.push_back({x, y});
  p.tool_on = tool_on;
  bool arcs = false;
  for (double b : bulge) arcs = arcs || b != 0.0;
  if (arcs) p.bulge = bulge;
  return p;
}

/// A profile as Python gives it (a dict of kind, sigma, beta, rate, depth) read into the command
/// line's options; the values are checked by fluxProfileOf, as the command line's are. A key it
/// does not know, a kind that is not a string or a value that is not a number is InputError.
/// Called with the GIL held.
ProfileOptions profileOptions(const py::dict& profile) {
  ProfileOptions o;
  // A str that is not text (a lone surrogate) cannot become UTF-8: one line, as for any bad value.
  const auto text = [](const py::handle& v, const std::string& field) {
    try {
      return v.cast<std::string>();
    } catch (const py::cast_error&) {
      throw InputError("profile", field, "is not valid text (a lone surrogate)");
    } catch (const py::error_already_set&) {
      throw InputError("profile", field, "is not valid text (a lone surrogate)");
    }
  };
  for (const auto& [k, v] : profile) {
    const std::string key = text(py::str(k), "(key)");
    if (key == "kind") {
      if (!py::isinstance<py::str>(v)) throw InputError("profile", "kind", "must be a string: none, uniform, gaussian or beta");
      o.profile = text(v, "kind");
      continue;
    }
    if (key == "flow") {
      if (!py::isinstance<py::str>(v)) throw InputError("profile", "flow", "must be a string: constant or speed");
      o.flow = text(v, "flow");
      continue;
    }
    std::optional<double>* value = key == "sigma" ? &o.sigma
                                   : key == "beta" ? &o.beta
                                   : key == "rate" ? &o.rate
                                   : key == "depth" ? &o.fan_depth
                                   : key == "target" ? &o.target
                                                    : nullptr;
    if (!value) throw InputError("profile", key, "is not a profile key (kind, sigma, beta, rate, depth, target, flow)");
    if (py::isinstance<py::bool_>(v) || !(py::isinstance<py::float_>(v) || py::isinstance<py::int_>(v)))
      throw InputError("profile", key, "must be a number");
    *value = v.cast<double>();
  }
  return o;
}

/// Python's spelling of profile errors: "profile: sigma: belongs to kind gaussian".
const ProfileSpelling kPythonProfile{"kind", "sigma", "beta", "rate", "depth", "target", "flow", "profile", "profile"};

/// The tool: its shape, its width, clearance and a rectangle's depth checked as the command line
/// checks them, then its profile.
ToolParams toolOf(double tool_width, double clearance, const std::string& shape, double depth, const ProfileOptions& profile) {
  ToolParams tool{tool_width, clearance};
  if (!parseToolShape(shape, tool.shape)) throw InputError("tool_shape", "tool.shape", toolShapeProblem(shape));
  tool.depth = depth;
  validateTool(tool, "tool");
  tool.profile = fluxProfileOf(profile, tool_width, kPythonProfile);
  return tool;
}

/// The five coat metrics (docs/deposition.md) by name, or none without a profile's coat.
void addCoat(ordered_json& out, const PathMetrics& metrics) {
  for (const NamedMetric& m : flatten(metrics))
    if (m.name == "thickness_mean" || m.name == "thickness_cv" || m.name == "even_share" || m.name == "thin_share" ||
        m.name == "thick_share")
      out[m.name] = number(m.value);
}

std::string plan(const std::string& wall_text, const std::string& planner, const std::string& params_json, double tool_width,
                 double clearance, std::uint64_t seed, double time_limit_s, double memory_mb, const ProfileOptions& profile,
                 const std::string& tool_shape, double tool_depth) {
  const Wall wall = wallOf(wall_text, "wall");
  const PlannerInfo& info = external::plannerNamed(planner, "planner");
  validateTimeLimit(time_limit_s, "time_limit_s", "time_limit_s");
  if (!(memory_mb > 0.0 && memory_mb <= 1048576.0))
    throw InputError("memory_mb", "memory_mb", "must be in (0, 1048576] MiB, got " + shortNumber(memory_mb));
  ProblemInputs inputs;
  inputs.wall = &wall;
  inputs.tool = toolOf(tool_width, clearance, tool_shape, tool_depth, profile);
  const nlohmann::json params = parseJsonStrict(params_json, "params");
  if (!params.is_object()) throw InputError("params", "(document)", "must be a mapping of name: value");
  inputs.params = withDefaults(info, parseSettingsJson(info, params, "params"));
  inputs.seed = seed;
  inputs.memory_limit_bytes = static_cast<std::size_t>(memory_mb * 1024.0 * 1024.0);
  const Problem problem = buildProblem(info, std::move(inputs), "tool");
  // Planned and judged as `coverbench plan` and a run judge it (one code path): a path that fails
  // the validity check is invalid_output, one beyond the scoring limits metrics_error.
  const JudgedPlan judged = planAndJudge(info, problem, Budget(std::chrono::duration<double>(time_limit_s)));
  const PlanResult& r = judged.result;
  ordered_json out = {{"planner", info.name}, {"status", toString(judged.verdict)}, {"reason", judged.reason},
                      {"planner_status", toString(r.status)}};
  const bool scored = r.hasPath() && judged.not_scored.empty();
  if (scored) {
    out.update(validityJson(judged.metrics.validity, problem.tool.clearance));
    addCoat(out, judged.metrics);
  } else {  // no path, or one beyond the scoring limits: nothing was checked
    out["valid"] = false;
    out["violations"] = nullptr;
    out["violating_segments"] = nullptr;
    out["violation_details"] = nullptr;
    out["invalid_reason"] = nullptr;
  }
  out["not_scored"] = judged.not_scored;
  ordered_json w = ordered_json::array();
  for (const Point& p : r.path.waypoints) w.push_back({p.x, p.y});
  out["waypoints"] = w;
  out["tool_on"] = r.path.tool_on;
  if (r.path.hasArcs()) out["bulge"] = r.path.bulge;
  out["stats"] = r.stats;
  out["plan_time_ms"] = r.plan_time_ms;
  return out.dump();
}

std::string score(const std::string& wall_text, const std::vector<std::pair<double, double>>& waypoints,
                  const std::vector<bool>& tool_on, const std::vector<double>& bulge, double tool_width, double clearance,
                  const std::string& judge, const ProfileOptions& profile, const std::string& tool_shape,
                  double tool_depth) {
  const Wall wall = wallOf(wall_text, "wall");
  const ToolParams tool = toolOf(tool_width, clearance, tool_shape, tool_depth, profile);
  validateToolForWall(tool, wall, "tool");  // the same check a plan's problem gets (buildProblem)
  const Path path = pathOf(waypoints, tool_on, bulge);
  ordered_json out = ordered_json::object();
  const PathMetrics metrics = computeMetrics(wall, tool, path);
  for (const NamedMetric& m : flatten(metrics)) out[m.name] = number(m.value);
  out.update(validityJson(metrics.validity, tool.clearance));  // valid as a bool, not the metric's 1 or 0
  if (judge == "exact") {
    const judge::Judgement j = judge::judgePath(wall, tool, path);
    out["exact"] = {{"valid", j.validity.valid},
                    {"violations", j.validity.violations},
                    {"coverage_reachable", {j.coverage.coverage_reachable.lower, j.coverage.coverage_reachable.upper}},
                    {"coverage_wall", {j.coverage.coverage_wall.lower, j.coverage.coverage_wall.upper}}};
  } else if (judge != "fast") {
    throw InputError("judge", "judge", "must be fast or exact, not '" + judge + "'");
  }
  return out.dump();
}

std::string runs(const std::string& database, long long experiment) {
  ResultsDb db(database, ResultsDb::Mode::ReadOnly);
  return renderRuns(db.load(experiment > 0 ? std::optional<long long>(experiment) : std::nullopt), true);
}

}  // namespace
}  // namespace coverbench

PYBIND11_MODULE(_core, m) {
  m.doc() = "CoverBench's C++ (walls, planners, the fast engine, the exact judge, results), JSON in and out";
  // Bad input is a ValueError with the command line's one-line message.
  py::register_exception<coverbench::InputError>(m, "InputError", PyExc_ValueError);
  m.def("check_wall", [](const std::string& text, const std::string& source) { coverbench::wallOf(text, source); },
        py::arg("text"), py::arg("source") = "wall",
        "Checks wall-file JSON text as the command line does; raises ValueError (SOURCE: FIELD: PROBLEM).");
  m.def("wall_file", [](const std::string& path) { return coverbench::wallToJson(coverbench::loadWallFile(path)); },
        py::arg("path"), "The wall file at `path`, checked, as wall-file JSON text.");
  m.def("planners", &coverbench::planners, "Every registered planner with its parameters, as JSON text.");
  m.def("plan",
        [](const std::string& wall, const std::string& planner, const std::string& params, double tool_width, double clearance,
           std::uint64_t seed, double time_limit_s, double memory_mb, const py::dict& profile, const std::string& tool_shape,
           double tool_depth) {
          const coverbench::ProfileOptions options = coverbench::profileOptions(profile);
          py::gil_scoped_release released;
          return coverbench::plan(wall, planner, params, tool_width, clearance, seed, time_limit_s, memory_mb, options, tool_shape,
                                  tool_depth);
        },
        py::arg("wall"), py::arg("planner"), py::arg("params"), py::arg("tool_width"), py::arg("clearance"), py::arg("seed"),
        py::arg("time_limit_s"), py::arg("memory_mb") = 4096.0, py::arg("profile") = py::dict(), py::arg("tool_shape") = "disk",
        py::arg("tool_depth") = 0.0,
        "Plans wall-file JSON text with a registered planner or an external planner's manifest and judges the "
        "path as `coverbench plan` does; the plan as JSON text.");
  m.def("score",
        [](const std::string& wall, const std::vector<std::pair<double, double>>& waypoints, const std::vector<bool>& tool_on,
           const std::vector<double>& bulge, double tool_width, double clearance, const std::string& judge,
           const py::dict& profile, const std::string& tool_shape, double tool_depth) {
          const coverbench::ProfileOptions options = coverbench::profileOptions(profile);
          py::gil_scoped_release released;
          return coverbench::score(wall, waypoints, tool_on, bulge, tool_width, clearance, judge, options, tool_shape, tool_depth);
        },
        py::arg("wall"), py::arg("waypoints"), py::arg("tool_on"), py::arg("bulge"), py::arg("tool_width"),
        py::arg("clearance"), py::arg("judge"), py::arg("profile") = py::dict(), py::arg("tool_shape") = "disk",
        py::arg("tool_depth") = 0.0,
        "Every metric of the fast engine for a path (judge 'exact' adds the exact judge's verdict; a flux `profile` "
        "adds the coat's five), as JSON text.");
  m.def("runs", &coverbench::runs, py::arg("database"), py::arg("experiment") = 0,
        "An experiment's runs (0: the latest) from a results database, as JSON text.");
}
