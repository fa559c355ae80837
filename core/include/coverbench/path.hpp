#pragma once
/// A path and the tool that follows it: the value types planners produce and judges score.

#include <cstddef>
#include <string>
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

/// How the robot carries its tool between passes (docs/vehicles.md). Part of a problem like the
/// tool: planners plan for it, the metrics engine validates and times a path by its rules.
struct VehicleModel {
  enum class Kind {
    /// The tool is a disk dragged over the wall: every move, tool on or off, stays in the free
    /// region F (a mower among trees). The default: every result before vehicle models is this.
    Holonomic,
    /// The tool retracts: a tool-off move is made with the tool lifted off the wall, so it may
    /// cross obstacles and leave F, within the wall's bounding box (the gantry's frame). Every
    /// run of tool-on moves is preceded by lowering the tool and followed by lifting it.
    Gantry,
  };
  Kind kind = Kind::Holonomic;
  double lift_s = 1.0;   ///< gantry: time to lift the tool off the wall (s)
  double lower_s = 1.0;  ///< gantry: time to lower it onto the wall (s)

  /// Tool-off moves may leave F (they are made with the tool lifted).
  bool liftsTool() const { return kind == Kind::Gantry; }
  bool isDefault() const { return kind == Kind::Holonomic; }
};
/// "holonomic" or "gantry".
std::string toString(VehicleModel::Kind kind);
/// The kind named `name`; false when there is none.
bool parseVehicleKind(const std::string& name, VehicleModel::Kind& kind);

}  // namespace coverbench
