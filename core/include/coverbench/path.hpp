#pragma once
/// A path and the tool that follows it: the value types planners produce and judges score.

#include <cstddef>
#include <vector>

#include "coverbench/geometry.hpp"

namespace coverbench {

/// A polyline of waypoints; `tool_on[i]` says whether segment i (waypoints[i] -> waypoints[i+1])
/// covers (tool on) or only moves (transit, tool off). tool_on.size() == waypoints.size() - 1.
struct Path {
  std::vector<Point> waypoints;
  std::vector<bool> tool_on;

  /// Appends a waypoint reached by a segment with the given tool state (the first waypoint
  /// starts the path). Repeated points are dropped.
  void moveTo(Point p, bool tool);
  std::size_t segments() const { return tool_on.size(); }
};

/// The tool and clearance of a problem (metres).
struct ToolParams {
  double tool_width = 0.1;  ///< s: the tool is a disk of diameter s centred on the path
  double clearance = 0.02;  ///< c: minimum gap between the tool disk and any obstacle
  double radius() const { return tool_width / 2.0; }
};

}  // namespace coverbench
