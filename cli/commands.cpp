#include "commands.hpp"
#include "coverbench/external_planner.hpp"
#include "coverbench/results_db.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <cstdio>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <sys/resource.h>
#include <unistd.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "coverbench/car_ceiling.hpp"
#include "coverbench/escape.hpp"
#include "coverbench/experiment.hpp"
#include "coverbench/judge.hpp"
#include "coverbench/limits.hpp"
#include "coverbench/metrics.hpp"
#include "coverbench/plan_file.hpp"
#include "coverbench/problem_builder.hpp"
#include "coverbench/registry.hpp"
#include "coverbench/run_planner.hpp"
#include "coverbench/svg.hpp"
#include "coverbench/region_ops.hpp"
#include "coverbench/wall_file.hpp"
#include "coverbench/workspace.hpp"

namespace coverbench::cli {

std::vector<std::pair<std::string, std::string>> splitSettings(const std::vector<std::string>& items) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const std::string& item : items) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0) throw InputError("--param", shownBytes(item), "expected key=value");
    out.emplace_back(item.substr(0, eq), item.substr(eq + 1));
  }
  return out;
}


namespace {

namespace fs = std::filesystem;

/// --tool-shape's value: disk or line.
ToolShape toolShapeOption(const std::string& name) {
  ToolShape shape = ToolShape::Disk;
  if (!parseToolShape(name, shape))
    throw InputError("--tool-shape", "tool.shape", toolShapeProblem(name));
  return shape;
}

/// The command line's vehicle over `base` (the default, or the plan file's), checked.
VehicleModel resolveVehicle(const VehicleOptions& given, VehicleModel base) {
  if (given.model && !parseVehicleKind(*given.model, base.kind))
    throw InputError("--vehicle", "vehicle", "must be holonomic, gantry or car, not '" + shownBytes(*given.model) + "'");
  if ((given.lift_s || given.lower_s) && !base.liftsTool())
    throw InputError(given.lift_s ? "--lift-s" : "--lower-s", "vehicle",
                     std::string("lift and lower times belong to a gantry (--vehicle gantry); ") +
                         (base.isCar() ? "a car" : "a holonomic vehicle") + " never lifts its tool");
  if ((given.turn_radius || given.reverse) && !base.isCar())
    throw InputError(given.turn_radius ? "--turn-radius" : "--reverse", "vehicle",
                     "a turn radius and reversing belong to a car (--vehicle car)");
  if (given.lift_s) base.lift_s = *given.lift_s;
  if (given.lower_s) base.lower_s = *given.lower_s;
  if (given.turn_radius) base.turn_radius = *given.turn_radius;
  if (given.reverse) base.reverse = true;
  validateVehicle(base, "command line", "vehicle");
  return base;
}

struct Outcome {
  PlanFile plan;
  std::string plan_json;
  std::string svg;
};

/// This process's resident set now, and its peak so far (bytes).
double residentBytes() {
  std::ifstream in("/proc/self/statm");
  double size = 0, resident = 0;
  in >> size >> resident;
  return resident * static_cast<double>(::sysconf(_SC_PAGESIZE));
}
double peakResidentBytes() {
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) * 1024.0;
}

/// Plans one wall with one planner and renders its outputs (nothing is written here). A path
/// beyond the scoring limits is kept, unscored, with the reason.
Outcome planOnce(const Wall& wall, const PlannerInfo& planner, const ToolParams& tool, const VehicleModel& vehicle,
                 Params params, double time_limit_s, bool with_picture, const TransitSpec& transit = {},
                 std::uint64_t seed = 0) {
  ProblemInputs inputs;
  inputs.wall = &wall;
  inputs.tool = tool;
  inputs.vehicle = vehicle;
  inputs.transit = transit;
  inputs.seed = seed;
  inputs.params = params;  // an external planner's processes: the default memory limit (ProblemInputs)
  const Problem problem = buildProblem(planner, std::move(inputs), "command line");
  Outcome o;
  o.plan.planner = planner.name;
  o.plan.wall = wall.name;
  o.plan.tool = tool;
  o.plan.start = wall.start;
  o.plan.end = wall.end;
  o.plan.vehicle = vehicle;
  o.plan.transit = transit;
  o.plan.seed = seed;
  o.plan.params = std::move(params);
  const double rss_before = residentBytes();
  // Planned and judged as Python's coverbench.plan and a run judge it (planAndJudge).
  JudgedPlan judged = planAndJudge(planner, problem, Budget(std::chrono::duration<double>(time_limit_s)));
  // The process's peak resident set grew by this much during the plan (0 if an earlier peak was
  // higher); an external planner's: its own processes' peak.
  o.plan.peak_memory_bytes = std::isfinite(judged.result.process_peak_bytes)
                                 ? judged.result.process_peak_bytes
                                 : std::max(0.0, peakResidentBytes() - rss_before);
  o.plan.result = std::move(judged.result);
  o.plan.metrics = judged.metrics;
  o.plan.not_scored = judged.not_scored;
  // The plan file's reason says why its coat's metrics are null (a raster past the cap).
  o.plan.result.reason = withNote(o.plan.result.reason, coatNotScoredNote(judged.metrics));
  o.plan.result.reason = withNote(o.plan.result.reason, toolShapeNote(planner, tool, o.plan.result));
  o.plan_json = planFileJson(o.plan);
  const bool scored = o.plan.not_scored.empty();
  const std::string title = wall.name + " / " + planner.name + "  (" + toolLabel(tool) + ")  " +
                            toString(o.plan.result.status) +
                            (!o.plan.result.hasPath()          ? ""
                             : !scored                         ? ", NOT SCORED"
                             : o.plan.metrics.validity.valid   ? ", valid"
                                                               : ", INVALID");
  if (with_picture) o.svg = pathPicture(wall, tool, vehicle, o.plan.result.path, title, scored);
  return o;
}

bool succeeded(const PlanFile& plan) {
  return plan.result.status == PlanStatus::Ok && plan.not_scored.empty() && plan.metrics.validity.valid;
}

std::string formatted(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

std::string percent(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f%%", 100.0 * v);
  return buf;
}

}  // namespace

void listPlanners(std::ostream& out) {
  for (const PlannerInfo& p : registeredPlanners()) {
    out << p.name << ": " << p.summary << "\n";
    out << "  reference: " << p.reference << "\n";
    for (const ParamSpec& s : p.params) {
      out << "  --param " << s.name << "=<" << paramTypeName(s.type) << ">  default " << paramText(s.default_value);
      if (s.type == ParamType::Number || s.type == ParamType::Integer)
        out << ", range [" << paramText(s.min) << ", " << paramText(s.max) << "]";
      if (!s.unit.empty()) out << " " << s.unit;
      out << "  " << s.description << "\n";
    }
  }
  out << "\ntransit planners (--transit, `transit:` in a config; docs/transits.md):\n";
  for (const TransitPlannerInfo& t : transitPlanners())
    out << t.name << ": " << t.summary << "\n  reference: " << t.reference << "\n";
}

namespace {

/// `X,Y` as a point; InputError naming `flag`.
Point pointOption(const std::string& text, const std::string& flag) {
  const std::size_t comma = text.find(',');
  // Decimal numbers only, as everywhere (strtod reads "0x1" and skips white space).
  if (text.find_first_of("xX \t\n\r\f\v") != std::string::npos)
    throw InputError(flag, "(value)", "must be X,Y in metres, got '" + shownBytes(text) + "'");
  char* end = nullptr;
  const std::string xs = text.substr(0, comma), ys = comma == std::string::npos ? "" : text.substr(comma + 1);
  const double x = std::strtod(xs.c_str(), &end);
  const bool x_ok = !xs.empty() && *end == '\0';
  const double y = std::strtod(ys.c_str(), &end);
  if (comma == std::string::npos || !x_ok || ys.empty() || *end != '\0' || !std::isfinite(x) || !std::isfinite(y))
    throw InputError(flag, "(value)", "must be X,Y in metres, got '" + shownBytes(text) + "'");
  return {x, y};
}

}  // namespace

int planCommand(const PlanOptions& options) {
  ToolParams tool = options.tool;
  tool.shape = toolShapeOption(options.tool_shape);
  validateTool(tool, "command line");
  validateTimeLimit(options.time_limit_s, "--time-limit", "time_limit");
  Wall wall = loadWallFile(options.wall);
  if (!options.start.empty()) wall.start = pointOption(options.start, "--start");
  if (options.end == "start") {
    if (!wall.start) throw InputError("--end", "(value)", "is start, but neither --start nor the wall file gives one");
    wall.end = wall.start;
  } else if (!options.end.empty()) {
    wall.end = pointOption(options.end, "--end");
  }
  if (!options.start.empty() || !options.end.empty()) validateWall(wall, "--start/--end");
  const PlannerInfo& planner = external::plannerNamed(options.planner, "--planner");
  Params params = resolveParams(planner, splitSettings(options.params));
  const VehicleModel vehicle = resolveVehicle(options.vehicle, VehicleModel{});
  const TransitPlannerInfo* transit = findTransitPlanner(options.transit.planner);
  if (!transit) throw InputError("--transit", "transit", "'" + shownBytes(options.transit.planner) + "' is not a transit planner (see `coverbench planners`)");
  if (!transit->sampling && options.transit_options_given)
    throw InputError("--transit-iterations", "transit", "iterations and a time cap belong to a sampling planner; visibility has neither");
  if (options.transit.iterations < 1 || options.transit.iterations > kMaxTransitIterations)
    throw InputError("--transit-iterations", "transit.iterations", "must be from 1 to " + std::to_string(kMaxTransitIterations));
  validateTimeLimit(options.transit.time_cap_s, "--transit-time-cap", "transit.time_cap_s");
  if (options.seed > (1ULL << 53)) throw InputError("--seed", "seed", "must be from 0 to 2^53");
  if (transit->sampling) loadSamplingTransits();
  tool.profile = fluxProfileOf(options.coat, tool.tool_width);
  const Outcome o = planOnce(wall, planner, tool, vehicle, std::move(params), options.time_limit_s,
                             !options.svg.empty(), options.transit, options.seed);
  OutputFiles files;  // both files or neither
  files.add(options.out, o.plan_json);
  if (!options.svg.empty()) files.add(options.svg, o.svg);
  files.commit();
  const PlanResult& r = o.plan.result;
  const PathMetrics& m = o.plan.metrics;
  std::cout << planner.name << " on " << wall.name << ": " << toString(r.status)
            << (r.reason.empty() ? "" : " (" + r.reason + ")") << ", " << r.path.waypoints.size() << " waypoints, ";
  if (!o.plan.not_scored.empty())
    std::cout << "NOT SCORED: " << o.plan.not_scored;
  else
    std::cout << (m.validity.valid ? "valid" : "INVALID: " + describeViolations(m.validity, options.tool.clearance))
              << ", coverage " << percent(m.coverage.coverage_reachable) << " of reachable";
  std::cout << ", " << r.plan_time_ms << " ms\n";
  return succeeded(o.plan) ? 0 : 3;
}

namespace {

// The scoring time limit of `coverbench metrics`: exact scoring runs inside Clipper, which cannot
// be interrupted, so the process itself ends at the deadline, with the documented one-line error
// and exit code 2; nothing has been written or printed by then.
char g_scoring_limit_message[512];

extern "C" void scoringTimeLimitReached(int) {
  const ssize_t ignored = ::write(STDERR_FILENO, g_scoring_limit_message, std::strlen(g_scoring_limit_message));
  (void)ignored;
  ::_exit(2);
}

void limitScoringTime(const std::string& plan_file, double seconds) {
  std::snprintf(g_scoring_limit_message, sizeof g_scoring_limit_message,
                "coverbench: %s: (scoring): not scored within the time limit of %g s (--time-limit)\n",
                plan_file.c_str(), seconds);
  std::signal(SIGALRM, scoringTimeLimitReached);
  ::alarm(static_cast<unsigned>(std::ceil(seconds)));
}

nlohmann::ordered_json intervalJson(const judge::Interval& i) { return {i.lower, i.upper}; }

/// The fast engine's metrics, the exact judge's figures, and how far the first lie from the second.
std::string judgedJson(const PathMetrics& m, const judge::Judgement& j) {
  using nlohmann::ordered_json;
  ordered_json doc;
  doc["metrics"] = ordered_json::parse(metricsJson(m));
  const judge::ExactCoverage& c = j.coverage;
  ordered_json exact;
  exact["method"] =
      "CGAL exact kernel: validity by exact squared distances, no tolerance; areas certified [lower, upper] "
      "from inscribed and circumscribed disk polygons with exact Booleans";
  exact["arc_vertices"] = c.arc_vertices;
  exact["valid"] = j.validity.valid;
  exact["violations"] = j.validity.violations;
  exact["outside_boundary"] = j.validity.outside_boundary;
  exact["too_close"] = j.validity.too_close;
  exact["coverage_reachable"] = intervalJson(c.coverage_reachable);
  exact["coverage_wall"] = intervalJson(c.coverage_wall);
  exact["reachable_area"] = intervalJson(c.reachable_area);
  exact["paintable_area"] = intervalJson(c.paintable_area);
  exact["swept_area"] = intervalJson(c.swept_area);
  doc["exact_judge"] = exact;
  ordered_json diff;
  diff["valid_agrees"] = m.validity.valid == j.validity.valid;
  diff["violations"] = static_cast<long long>(m.validity.violations) - static_cast<long long>(j.validity.violations);
  diff["coverage_reachable"] = c.coverage_reachable.offset(m.coverage.coverage_reachable);
  diff["coverage_wall"] = c.coverage_wall.offset(m.coverage.coverage_wall);
  diff["reachable_area"] = c.reachable_area.offset(m.coverage.reachable_area);
  diff["paintable_area"] = c.paintable_area.offset(m.coverage.paintable_area);
  diff["swept_area"] = c.swept_area.offset(m.coverage.swept_area);
  doc["fast_outside_exact"] = diff;
  return doc.dump(2) + "\n";
}

}  // namespace

int carCeilingCommand(const CarCeilingCommandOptions& options) {
  const Wall wall = loadWallFile(options.wall);
  validateToolForWall(options.tool, wall, "command line");
  VehicleModel car;  // the range `plan` holds a car's turn radius to, with its one-line error
  car.kind = VehicleModel::Kind::Car;
  car.turn_radius = options.turn_radius;
  validateVehicle(car, "command line", "vehicle");
  if (!(options.resolution >= 0.001 && options.resolution <= 1.0))
    throw InputError("--resolution", "resolution", "must be in [0.001, 1] m, got " + shortNumber(options.resolution));
  if (options.headings < 8 || options.headings > 720)
    throw InputError("--headings", "headings", "must be from 8 to 720, got " + std::to_string(options.headings));
  CarCeilingOptions o;
  o.turn_radius = options.turn_radius;
  o.resolution = options.resolution;
  o.headings = options.headings;
  const CarCeiling c = forwardCarCeiling(wall, options.tool, o);
  nlohmann::ordered_json doc;
  doc["wall"] = wall.name;
  doc["tool_width"] = options.tool.tool_width;
  doc["clearance"] = options.tool.clearance;
  doc["turn_radius"] = options.turn_radius;
  doc["resolution"] = c.resolution;
  doc["headings"] = c.headings;
  doc["step"] = c.step;
  doc["states"] = c.states;
  doc["viable_states"] = c.viable;
  doc["pieces_of_f"] = c.pieces;
  doc["viable_components"] = c.components;
  doc["reachable_area"] = c.reachable_area;
  doc["interior_area"] = c.interior_area;
  doc["with_ends_area"] = c.with_ends_area;
  doc["interior"] = c.interior;
  doc["with_ends"] = c.with_ends;
  doc["largest_piece_area"] = c.largest_piece_area;
  doc["largest_piece"] = c.largest_piece;
  std::cout << doc.dump(2) << "\n";
  return 0;
}

int metricsCommand(const MetricsOptions& options) {
  validateTimeLimit(options.time_limit_s, "--time-limit", "time_limit");
  if (options.arc_vertices < 8 || options.arc_vertices % 8 != 0 || options.arc_vertices > 4096)
    throw InputError("--arc-vertices", "arc_vertices", "must be a multiple of 8 from 8 to 4096");
  Wall wall = loadWallFile(options.wall);
  const LoadedPlan plan = loadPlanFile(options.plan);
  // The start and end the plan was made for (over the wall file's): its depot legs' ends.
  if (plan.start) wall.start = plan.start;
  if (plan.end) wall.end = plan.end;
  ToolParams tool;
  tool.tool_width = options.tool_width ? *options.tool_width : plan.tool_width.value_or(tool.tool_width);
  tool.clearance = options.clearance ? *options.clearance : plan.clearance.value_or(tool.clearance);
  tool.shape = options.tool_shape ? toolShapeOption(*options.tool_shape) : plan.tool_shape.value_or(ToolShape::Disk);
  // A rectangle's depth: the command line's, else the plan file's when it is a rectangle too.
  tool.depth = options.tool_depth ? *options.tool_depth : tool.isRectangle() ? plan.tool_depth.value_or(0.0) : 0.0;
  validateToolForWall(tool, wall, options.tool_width || options.clearance || options.tool_depth ? "command line" : options.plan);
  MotionLimits limits;
  limits.speed = options.speed;
  limits.acceleration = options.acceleration;
  // The config's bounds (motion.speed, motion.acceleration): slower than a micrometre a second, a
  // duration or a constant gun's coat may pass what a double holds.
  if (!(limits.speed >= kMinMotion && limits.speed <= kMaxMotion))
    throw InputError("--speed", "speed", "must be in [1e-06, 1000] m/s, got " + shortNumber(limits.speed));
  if (!((limits.acceleration >= kMinMotion && limits.acceleration <= kMaxMotion) || limits.acceleration == HUGE_VAL))
    throw InputError("--acceleration", "acceleration", "must be in [1e-06, 1000] m/s^2 (inf: no ramp), got " + shortNumber(limits.acceleration));
  if (options.stops != "turns" && options.stops != "waypoints")
    throw InputError("--stops", "stops", "must be turns or waypoints, got '" + shownBytes(options.stops) + "'");
  limits.stops = options.stops == "waypoints" ? MotionLimits::Stops::Waypoints : MotionLimits::Stops::Turns;
  limits.stop_angle_deg = options.stop_angle;
  if (!(limits.stop_angle_deg > 0.0 && limits.stop_angle_deg < 180.0))
    throw InputError("--stop-angle", "stop_angle", "must be in (0, 180) degrees, got " + shortNumber(options.stop_angle));
  limits.turn_cost_s = options.turn_cost;
  if (!(limits.turn_cost_s >= 0.0 && limits.turn_cost_s <= 3600.0))
    throw InputError("--turn-cost", "turn_cost_s", "must be in [0, 3600] s, got " + shortNumber(options.turn_cost));
  limits.rotation_speed = options.rotation_speed;
  if (!(limits.rotation_speed >= 0.0 && limits.rotation_speed <= 100.0))
    throw InputError("--rotation-speed", "rotation_speed", "must be in [0, 100] rad/s, got " + shortNumber(options.rotation_speed));
  // The command line's profile, else the plan file's (the one its rows may have been spaced for).
  const ProfileOptions& coat = options.coat;
  if (coat.named || coat.sigma || coat.beta || coat.rate || coat.fan_depth || coat.target || coat.flow || !plan.profile) {
    tool.profile = fluxProfileOf(coat, tool.tool_width);
  } else {
    tool.profile = *plan.profile;
    tool.profile.check(tool.tool_width, options.plan + ": profile");
  }
  if (!options.coat_svg.empty() && !tool.profile.set())
    throw InputError("--coat-svg", "profile", "the coat's picture needs the tool's flux profile (--profile)");
  limitScoringTime(options.plan, options.time_limit_s);
  const VehicleModel vehicle = resolveVehicle(options.vehicle, plan.vehicle.value_or(VehicleModel{}));
  Coat scored_coat;  // the coat the metrics were computed in, drawn by --coat-svg
  const bool draw_coat = !options.coat_svg.empty();
  const PathMetrics m =
      computeMetrics(wall, tool, plan.path, vehicle, limits, draw_coat ? &scored_coat : nullptr, draw_coat ? coatBlockCells(wall, tool) : 0);
  // Asked to score the coat, the command fails when it cannot (a raster past the cap): deposition()
  // throws its one-line error before any raster work.
  if (!m.coat_not_scored.empty()) deposition(wall, tool, plan.path, tool.profile, limits, vehicle);
  std::optional<judge::Judgement> exact;
  if (options.judge == "exact") {
    judge::CoverageOptions judge_options;
    judge_options.arc_vertices = options.arc_vertices;
    exact = judge::judgePath(wall, tool, plan.path, vehicle, judge_options);
  }
  OutputFiles files;  // the picture is written before anything is printed, so a failure prints nothing
  if (!options.svg.empty()) files.add(options.svg, pathPicture(wall, tool, vehicle, plan.path, wall.name + " / " + options.plan));
  if (!options.coat_svg.empty())
    files.add(options.coat_svg, coatPicture(wall, tool, scored_coat, wall.name + " / " + options.plan + ": the coat"));
  ::alarm(0);
  files.commit();
  // Where an invalid path goes wrong, on stderr (the JSON on stdout keeps its keys).
  if (!m.validity.valid) std::fprintf(stderr, "invalid path: %s\n", describeViolations(m.validity, tool.clearance).c_str());
  if (m.validity.depot_legs > 0)
    std::fprintf(stderr, "depot legs: %zu, %.6g m (fast judge)\n", m.validity.depot_legs, m.validity.depot_length);
  if (exact && exact->validity.depot_legs > 0)
    std::fprintf(stderr, "depot legs: %zu, %.6g m (exact judge)\n", exact->validity.depot_legs, exact->validity.depot_length);
  if (!exact) {
    std::cout << metricsJson(m);
    return m.validity.valid ? 0 : 3;
  }
  // The time is a measurement: it goes to stderr, so the JSON stays the same at every run.
  std::fprintf(stderr, "exact judge: %.2f s (validity %.2f s, areas %.2f s)\n",
               exact->seconds_validity + exact->seconds_coverage, exact->seconds_validity, exact->seconds_coverage);
  std::cout << judgedJson(m, *exact);
  return m.validity.valid && exact->validity.valid ? 0 : 3;
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
  for (const fs::path& f : files) {  // all input checked first
    walls.push_back(loadWallFile(f.string()));
    validateToolForWall(options.tool, walls.back(), "command line");
  }
  // File names come from wall and planner names through one path-safe, collision-free mapping.
  std::vector<std::string> names;
  for (const Wall& wall : walls)
    for (const PlannerInfo& planner : registeredPlanners()) names.push_back(wall.name + "__" + planner.name);
  const std::vector<std::string> stems = uniqueFileNames(names);

  const fs::path out = options.out;
  OutputFiles outputs;  // everything or nothing: staged, published at the end
  outputs.folder((out / "plans").string());
  const std::vector<std::string> header = {
      "wall", "planner", "status", "valid", "violations", "min clearance (m)", "coverage reachable", "coverage wall",
      "overlap", "length (m)", "transit (m)", "length ratio", "turns", "duration (s)", "waypoints", "plan time (ms)"};
  const std::vector<std::string> csv_header = {
      "wall", "planner", "status", "valid", "violations", "min_clearance_m", "coverage_reachable", "coverage_wall",
      "overlap", "length_m", "transit_m", "length_ratio", "turns", "duration_s", "waypoints", "plan_time_ms"};
  auto joined = [](const std::vector<std::string>& cells, std::string (*escape)(const std::string&),
                   const std::string& open, const std::string& sep, const std::string& close) {
    std::string line = open;
    for (std::size_t k = 0; k < cells.size(); ++k) line += (k ? sep : "") + escape(cells[k]);
    return line + close;
  };
  std::string table = joined(header, escapeMarkdown, "| ", " | ", " |\n") + "|";
  for (std::size_t k = 0; k < header.size(); ++k) table += "---|";
  table += "\n";
  std::string csv = joined(csv_header, escapeCsv, "", ",", "\n");
  // The page comes from the report machinery (reports/python): one layout, walls side by side.
  nlohmann::ordered_json rows = nlohmann::ordered_json::array(), walls_json = nlohmann::ordered_json::array();
  int exit_code = 0;
  std::size_t next_stem = 0;
  for (const Wall& wall : walls) {
    nlohmann::ordered_json pictures = nlohmann::ordered_json::array();
    for (const PlannerInfo& planner : registeredPlanners()) {
      const Outcome o = planOnce(wall, planner, options.tool, VehicleModel{}, resolveParams(planner, {}), 60.0, true);
      const std::string& stem = stems[next_stem++];
      outputs.add((out / "plans" / (stem + ".json")).string(), o.plan_json);
      outputs.add((out / "plans" / (stem + ".svg")).string(), o.svg);
      const PathMetrics& m = o.plan.metrics;
      const double mc = m.validity.min_clearance;
      const std::vector<std::string> cells = {
          wall.name, planner.name, toString(o.plan.result.status), !o.plan.not_scored.empty() ? "not scored" : m.validity.valid ? "yes" : "NO",
          std::to_string(m.validity.violations), std::isfinite(mc) ? shortNumber(mc) : "-",
          formatted("%.4f", m.coverage.coverage_reachable), formatted("%.4f", m.coverage.coverage_wall),
          formatted("%.4f", m.passes.overlap), formatted("%.2f", m.lengths.total), formatted("%.2f", m.lengths.transit),
          formatted("%.3f", m.length_ratio), std::to_string(m.motion.turns), formatted("%.1f", m.motion.duration_s),
          std::to_string(m.waypoints), formatted("%.2f", o.plan.result.plan_time_ms)};
      table += joined(cells, escapeMarkdown, "| ", " | ", " |\n");
      csv += joined(cells, escapeCsv, "", ",", "\n");
      rows.push_back(cells);
      const PictureSize size = pictureSize(wall, &o.plan.result.path);
      const std::string verdict = !o.plan.not_scored.empty() ? ", not scored" : m.validity.valid ? "" : ", INVALID";
      pictures.push_back({{"column", planner.name},
                          {"status", toString(o.plan.result.status) + verdict},
                          {"file", "plans/" + stem + ".svg"},
                          {"note", "plan file: plans/" + stem + ".json"},
                          {"width", std::llround(size.width)},
                          {"height", std::llround(size.height)}});
      if (!succeeded(o.plan)) exit_code = 3;
      std::cout << "  " << wall.name << " / " << planner.name << ": " << toString(o.plan.result.status)
                << (!o.plan.not_scored.empty() ? ", NOT SCORED" : m.validity.valid ? ", valid" : ", INVALID")
                << ", coverage " << percent(m.coverage.coverage_reachable) << " of reachable\n";
    }
    walls_json.push_back({{"wall_name", wall.name}, {"why", "every planner, default parameters"}, {"pictures", pictures}});
  }
  outputs.add((out / "summary.md").string(),
              "# CoverBench showcase\n\nTool width " + shortNumber(options.tool.tool_width) + " m, clearance " +
                  shortNumber(options.tool.clearance) +
                  " m, default planner parameters. Pictures and plan files are in `plans/`.\n\n" + table);
  outputs.add((out / "summary.csv").string(), csv);
  const std::string tool_text = "tool width " + shortNumber(options.tool.tool_width) + " m, clearance " +
                                shortNumber(options.tool.clearance) + " m";
  const nlohmann::ordered_json page = {
      {"format", "coverbench-showcase"},
      {"title", "CoverBench showcase"},
      {"subtitle", "Every wall of " + options.walls + " with every planner (" + tool_text +
                       ", default parameters). Every path is validated exactly; metric definitions: docs/metrics.md. "
                       "Plan files and pictures are in plans/, the table also in summary.md and summary.csv."},
      {"table", {{"title", "Every wall with every planner"}, {"header", header}, {"rows", rows}}},
      {"gallery", {{{"title", "Walls"}, {"walls", walls_json}}}}};
  outputs.add((out / "index.html").string(), renderShowcasePage(page.dump(1)));
  outputs.commit();
  std::cout << "summary table: " << (out / "summary.md").string() << "\nreport: " << (out / "index.html").string()
            << "\n";
  return exit_code;
}

int redrawCommand(const RedrawOptions& options) {
  ResultsDb db(options.database, ResultsDb::Mode::ReadOnly);
  const ResultsDb::StoredRun run = options.replan ? db.storedReplan(options.run, *options.replan) : db.storedRun(options.run);
  char title[512];
  std::snprintf(title, sizeof title, "%s / %s  (s = %g m, c = %g m)  %s", run.wall.name.c_str(), run.planner.c_str(),
                run.tool.tool_width, run.tool.clearance, run.status.c_str());
  if (!options.coat_svg.empty() && !run.tool.profile.set())
    throw InputError("--coat-svg", "tool.profile",
                     "run " + run.key.substr(0, 12) + "'s tool has no flux profile (its experiment's tool: gives none): it lays no coat to draw");
  OutputFiles files;  // both pictures or neither
  files.add(options.svg, pathPicture(run.wall, run.tool, run.vehicle, run.path, title, true, 1500.0, run.first_judged_segment));
  if (!options.coat_svg.empty())
    files.add(options.coat_svg, coatPicture(run.wall, run.tool, run.path, run.motion, run.vehicle, std::string(title) + ": the coat"));
  files.commit();
  std::cout << "run " << run.key << ": " << run.status << (run.reason.empty() ? "" : " (" + run.reason + ")") << ", "
            << run.path.waypoints.size() << " waypoints -> " << options.svg
            << (options.coat_svg.empty() ? "" : ", its coat -> " + options.coat_svg) << "\n";
  return 0;
}

}  // namespace coverbench::cli
