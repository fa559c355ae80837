#pragma once
/// Plan files (JSON): what `coverbench plan` writes and `coverbench metrics` reads.
/// Format: docs/file_formats.md.

#include <optional>
#include <string>

#include "coverbench/files.hpp"
#include "coverbench/metrics.hpp"
#include "coverbench/planner.hpp"

namespace coverbench {

struct PlanFile {
  std::string planner;
  std::string wall;
  ToolParams tool;
  /// The wall's start and end the plan was made for (written only when given: a wall file's or
  /// `--start`/`--end`), so that `coverbench metrics` judges its depot legs (path.hpp).
  std::optional<Point> start, end;
  VehicleModel vehicle;  ///< written only when not holonomic (older files, and holonomic ones, have none)
  TransitSpec transit;   ///< written only when not visibility, with the seed
  std::uint64_t seed = 0;  ///< the problem's seed (what a sampling transit planner draws from)
  Params params;
  PlanResult result;
  PathMetrics metrics;
  std::string not_scored;  ///< why the path was not scored (beyond the scoring limits); "" if it was
  std::optional<double> peak_memory_bytes;  ///< heap high-water mark of the plan call, if measured
};

/// The plan file as JSON text: one top-level key per line and one metric per line. Everything
/// but the last key, `measured` (plan time, peak memory, the planner's own timings), is a
/// deterministic function of the inputs.
std::string planFileJson(const PlanFile& plan);

/// The metrics object alone (what `coverbench metrics` prints): deterministic.
std::string metricsJson(const PathMetrics& metrics);

/// The described violations (Validity::described) as a JSON array, one object each:
/// {"segment", "from": [x, y], "to": [x, y], "outside_boundary", "lifted", "too_close",
/// "not_drivable", "boundary_gap", "clearance" (m; null where not measured), "obstacle" (index in
/// the wall's obstacles, null when none is named), "obstacle_label"}. For bindings (Python's score).
std::string violationsJson(const Validity& validity);

/// A path read from a plan file of any source: only `waypoints` and `tool_on` are required;
/// `tool_width`, `clearance`, `tool_shape`, `tool_depth`, `profile`, `start`, `end` and `vehicle` are read when present.
struct LoadedPlan {
  Path path;
  std::optional<double> tool_width;
  std::optional<double> clearance;
  std::optional<ToolShape> tool_shape;  ///< `tool_shape`; none: a disk (plan files before shapes)
  std::optional<double> tool_depth;     ///< `tool_depth`: a rectangle's d, and only a rectangle's
  std::optional<FluxProfile> profile;  ///< the tool's flux profile, not yet checked against its width
  std::optional<Point> start, end;
  std::optional<VehicleModel> vehicle;
};
/// The plan file's `vehicle` object: {"model": "gantry", "lift_s": 1, "lower_s": 1}.
std::string vehicleJson(const VehicleModel& vehicle);
/// The tool's flux profile as a plan file and protocol 2 write it: {"kind", "sigma" or "beta" for
/// their kinds, "rate", "depth" (resolved: s / 10 when 0), "target" only when there is one, "flow"
/// only when it follows the speed}; "null" for a tool without a profile.
std::string profileJson(const ToolParams& tool);
/// Throws InputError (file, field, problem) for anything malformed, and for paths beyond the
/// scoring limits (kMaxScoredWaypoints, kMaxPathCoordinate).
LoadedPlan loadPlanFile(const std::string& file);

}  // namespace coverbench
