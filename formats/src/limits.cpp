#include "coverbench/limits.hpp"

#include <cmath>
#include <cstdio>
#include <utility>

namespace coverbench {
void validateTool(const ToolParams& tool, const std::string& source) {
  if (!std::isfinite(tool.tool_width) || tool.tool_width < kMinToolWidth || tool.tool_width > kMaxToolWidth)
    throw InputError(source, "tool_width",
                     "must be in [" + shortNumber(kMinToolWidth) + ", " + shortNumber(kMaxToolWidth) + "] m, got " +
                         shortNumber(tool.tool_width) + (tool.tool_width > 0.0 && tool.tool_width < kMinToolWidth
                                                      ? " (a tool under 1 mm is finer than the exact area grid)"
                                                      : ""));
  if (!std::isfinite(tool.clearance) || tool.clearance < 0.0 || tool.clearance > kMaxClearance)
    throw InputError(source, "clearance", "must be in [0, " + shortNumber(kMaxClearance) + "] m, got " + shortNumber(tool.clearance));
  if (tool.isRectangle() && tool.depth == 0.0)
    throw InputError(source, "tool_depth", "is missing: a rectangle tool's depth along the heading, m");
  if (tool.isRectangle() && (!std::isfinite(tool.depth) || tool.depth < kMinToolWidth || tool.depth > kMaxToolWidth))
    throw InputError(source, "tool_depth",
                     "a rectangle's depth must be in [" + shortNumber(kMinToolWidth) + ", " + shortNumber(kMaxToolWidth) +
                         "] m, got " + shortNumber(tool.depth));
  if (!tool.isRectangle() && tool.depth != 0.0)
    throw InputError(source, "tool_depth", "a depth belongs to a rectangle; a " + toString(tool.shape) + " has none");
}

namespace {

double toolCells(const ToolParams& tool, const Wall& wall) {
  const Box b = boundingBox(wall.boundary);
  return b.width() * b.height() / (tool.tool_width * tool.tool_width);
}

}  // namespace

void validateToolForWall(const ToolParams& tool, const Wall& wall, const std::string& source) {
  validateTool(tool, source);
  const double cells = toolCells(tool, wall);
  if (cells > kMaxToolCells) {
    const Box b = boundingBox(wall.boundary);
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "%g m is too fine for wall '%s' (%.3g m x %.3g m): %.3g tool-sized cells, at most %.0e (no path of "
                  "that many rows could be scored)",
                  tool.tool_width, wall.name.c_str(), b.width(), b.height(), cells, kMaxToolCells);
    throw InputError(source, "tool_width", buf);
  }
}

std::string gridCellsProblem(const ToolParams& tool, const Wall& wall) {
  const double cells = toolCells(tool, wall);
  if (cells <= kMaxGridCells) return "";
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "a grid of %.3g tool-sized cells (%g m on this wall's bounding box) is more than a grid planner's %.0e "
                "(it allocates per cell: 1.2 GB at 1e7); the sweep planners need no grid",
                cells, tool.tool_width, kMaxGridCells);
  return buf;
}

void validateTimeLimit(double seconds, const std::string& source, const std::string& field) {
  if (!std::isfinite(seconds) || seconds <= 0.0 || seconds > kMaxTimeLimitSeconds)
    throw InputError(source, field, "must be in (0, " + shortNumber(kMaxTimeLimitSeconds) + "] s, got " + shortNumber(seconds));
}

void validateVehicle(const VehicleModel& vehicle, const std::string& source, const std::string& field) {
  for (const auto& [name, value] : {std::pair<const char*, double>{"lift_s", vehicle.lift_s}, {"lower_s", vehicle.lower_s}})
    if (!std::isfinite(value) || value < 0.0 || value > kMaxLiftTime)
      throw InputError(source, field + "." + name,
                       "must be in [0, " + shortNumber(kMaxLiftTime) + "] s, got " + shortNumber(value));
  if (!std::isfinite(vehicle.turn_radius) || vehicle.turn_radius < kMinTurnRadius || vehicle.turn_radius > kMaxTurnRadius)
    throw InputError(source, field + ".turn_radius",
                     "must be in [" + shortNumber(kMinTurnRadius) + ", " + shortNumber(kMaxTurnRadius) + "] m, got " +
                         shortNumber(vehicle.turn_radius) +
                         (vehicle.turn_radius > 0.0 && vehicle.turn_radius < kMinTurnRadius
                              ? " (a car that turns tighter than 1 cm turns all but on the spot: use the holonomic vehicle)"
                              : ""));
}

}  // namespace coverbench
