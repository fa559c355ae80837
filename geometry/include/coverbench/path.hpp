#pragma once
/// A path and the tool that follows it: the value types planners produce and judges score.

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "coverbench/flux_profile.hpp"
#include "coverbench/geometry.hpp"

namespace coverbench {

/// A path of waypoints; `tool_on[i]` says whether segment i (waypoints[i] -> waypoints[i+1])
/// covers (tool on) or only moves (transit, tool off). tool_on.size() == waypoints.size() - 1.
/// Segments are straight unless `bulge` says otherwise (docs/vehicles.md, the car).
struct Path {
  std::vector<Point> waypoints;
  std::vector<bool> tool_on;
  /// Empty (every segment straight: every path before the car), or one per segment: 0 for a
  /// straight segment, else the circular arc from waypoints[i] to waypoints[i+1] with bulge
  /// b = tan(phi / 4), phi its signed central angle (positive: counter-clockwise, a left turn),
  /// 0 < |b| <= 1 (at most a half circle per segment).
  std::vector<double> bulge;

  /// Appends a waypoint reached by a straight segment with the given tool state (the first
  /// waypoint starts the path). Repeated points are dropped.
  void moveTo(Point p, bool tool);
  /// Appends a waypoint reached along the arc of bulge `b` (0: straight). Repeated points are
  /// dropped; a bulge under kMinArcBulge or on a chord under kMinArcChord is a straight segment.
  void arcTo(Point p, double b, bool tool);
  std::size_t segments() const { return tool_on.size(); }
  /// Room for `count` more segments without reallocating (a curve built piece by piece).
  void reserve(std::size_t count) {
    waypoints.reserve(waypoints.size() + count + 1);
    tool_on.reserve(tool_on.size() + count);
    bulge.reserve(tool_on.size() + count);
  }
  double bulgeOf(std::size_t i) const { return bulge.empty() ? 0.0 : bulge[i]; }
  bool hasArcs() const;
};

/// The circle of an arc segment: centre, radius, and its signed central angle phi.
struct ArcGeometry {
  Point centre;
  double radius = 0.0;
  double sweep = 0.0;  ///< phi, radians; positive: counter-clockwise
};
/// The arc from a to b with bulge b (nonzero).
ArcGeometry arcGeometry(Point a, Point b, double bulge);

/// A bulge below this (a heading change of 2e-12 rad, far below a car's 1e-6 rad tolerance) is a
/// straight segment, and so is any bulge on a segment shorter than kMinArcChord (the arc stays
/// within half of it of its chord): as arcs, a bulge of 1e-200 puts the circle's centre beyond
/// any double and a bulge on a zero-length segment has no circle. Readers of paths and
/// Path::arcTo take such a bulge as 0.
inline constexpr double kMinArcBulge = 1e-12;
inline constexpr double kMinArcChord = 1e-9;  ///< m
/// The bulge as paths hold it: 0 for an arc under kMinArcBulge or kMinArcChord, else `b`.
double effectiveBulge(Point a, Point b, double bulge);
/// The length of segment i: the chord, or the arc's radius times |phi|.
double segmentLength(const Path& path, std::size_t i);

/// The tool's shape (docs/metrics.md#tool-shapes).
enum class ToolShape {
  Disk,  ///< a disk of diameter s centred on the path: the same in every heading
  /// A segment of length s centred on the path and square to its heading (a roller, a trowel, a
  /// mower deck, a line sensor): it sweeps a rectangle along a straight move and, where the
  /// heading turns, rotates about its centre by the smaller angle (a line is the same turned by
  /// half a circle), sweeping two opposite sectors of radius s / 2.
  Line,
  /// A rectangle s across the heading and d (ToolParams::depth) along it, centred on the path (a
  /// mower deck, a wide roller with its frame, a sanding pad): a line of depth d. Along a move it
  /// sweeps a rectangle d longer than the move; where the heading turns it rotates about its
  /// centre by the smaller angle (it too is the same turned by half a circle), sweeping four
  /// sectors of radius sqrt(s^2 + d^2) / 2, one from each corner.
  Rectangle,
};
/// "disk", "line" or "rectangle".
std::string toString(ToolShape shape);
/// The shape named `name`; false when there is none.
bool parseToolShape(const std::string& name, ToolShape& shape);
/// What every reader says of a shape that is none: "must be disk, line or rectangle, got 'NAME'", with bytes
/// outside printable ASCII as \xHH (one line of valid text whatever was given).
std::string toolShapeProblem(const std::string& name);

/// The tool and clearance of a problem (metres).
struct ToolParams {
  double tool_width = 0.1;  ///< s: the tool's width (a disk's diameter, a line's length)
  double clearance = 0.02;  ///< c: minimum gap between the tool and any obstacle
  FluxProfile profile = {};  ///< how it spreads what it sprays (none: a tool that only touches)
  ToolShape shape = ToolShape::Disk;
  double depth = 0.0;  ///< d: a rectangle's depth along the heading (0 for a disk or a line)
  double radius() const { return tool_width / 2.0; }
  bool isLine() const { return shape == ToolShape::Line; }
  bool isRectangle() const { return shape == ToolShape::Rectangle; }
  /// A line or a rectangle: what it covers turns with the heading (docs/metrics.md#tool-shapes).
  bool turnsWithHeading() const { return shape != ToolShape::Disk; }
  /// d / 2: how far the shape reaches ahead of and behind its centre (0 for a line).
  double halfDepth() const { return isRectangle() ? depth / 2.0 : 0.0; }
  /// The radius of the disk around the centre that holds the tool in every heading: s / 2, or
  /// half a rectangle's diagonal.
  double reachRadius() const { return std::hypot(radius(), halfDepth()); }
};
/// The disk that holds `tool` in every heading (diameter 2 reachRadius()), with its clearance and
/// profile: what a planner that plans for disks plans a rectangle for (a path valid for it is
/// valid for the rectangle, which lies in it at every heading).
ToolParams circumscribedDisk(const ToolParams& tool);
/// The tool as every table, column, title and message names it: "s=0.1 m, c=0.02 m" (a disk),
/// "line s=0.1 m, c=0.02 m", "rectangle s=0.23 m, d=0.05 m, c=0.02 m".
std::string toolLabel(const ToolParams& tool);
/// toolLabel, then the flux profile's label where there is one: "s=0.1 m, c=0.02 m, beta 2.5".
std::string toolAndProfileLabel(const ToolParams& tool);

/// Depot legs: a wall's start or end may lie anywhere in the closed wall off every obstacle (a
/// dock on an edge or at a corner), also where the tool's centre may not be (outside F: the tool
/// there overhangs the wall's edge or comes within c of an obstacle). A path from a start outside
/// F begins with a depot leg: its longest run of segments from the start, up to and including the
/// first one that ends at a waypoint in F, every waypoint before that one lying outside F. Each of
/// its segments must be straight and tool-off, with its centre line inside the wall or on its
/// edge and no point in common with any obstacle (the tool's body may overhang the edge and come
/// near or over an obstacle: the tool is off, driving from its dock). Likewise a path to an end
/// outside F ends with a depot leg from its last waypoint in F. Both judges check a depot leg by
/// this rule only (a leg that breaks it is checked segment by segment like any other, and then
/// fails); its end in F begins the next segment, checked as usual. It paints nothing and cannot
/// hide a painting or a move anywhere but between the dock and F: a path that never reaches a
/// waypoint in F has no depot leg. Its length and time count in the path's.
/// The runner builds them (run_planner.cpp: attachEnds): the straight move to the nearest point of
/// F when the rule allows it, else the shortest route around the obstacles.

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
    /// A car-like robot (a mower, a wall robot on wheels): every move stays in F like a holonomic
    /// one, but it drives lines and arcs of radius at least `turn_radius` with a continuous
    /// heading; with `reverse` (Reeds-Shepp) it may also stop and back up (a cusp), without it
    /// (Dubins) it never does. Its speed on an arc of radius R is at most sqrt(a R).
    Car,
  };
  Kind kind = Kind::Holonomic;
  double lift_s = 1.0;   ///< gantry: time to lift the tool off the wall (s)
  double lower_s = 1.0;  ///< gantry: time to lower it onto the wall (s)
  double turn_radius = 0.5;  ///< car: the smallest radius it turns on (m)
  bool reverse = false;      ///< car: it may reverse (Reeds-Shepp); false: forward only (Dubins)

  /// Tool-off moves may leave F (they are made with the tool lifted).
  bool liftsTool() const { return kind == Kind::Gantry; }
  bool isDefault() const { return kind == Kind::Holonomic; }
  bool isCar() const { return kind == Kind::Car; }
};

/// The heading change a car may make at a waypoint (radians): its heading is continuous, so what
/// the path's numbers leave between one segment's end tangent and the next one's start tangent
/// must be rounding, nothing a wheel would notice. At a cusp of a reversing car the two tangents
/// are opposite within the same tolerance.
inline constexpr double kCarHeadingTolerance = 1e-6;

/// "holonomic", "gantry" or "car".
std::string toString(VehicleModel::Kind kind);
/// The kind named `name`; false when there is none.
bool parseVehicleKind(const std::string& name, VehicleModel::Kind& kind);

/// The transit planner of a problem (config section `transit:`, `--transit` on the command line).
struct TransitSpec {
  std::string planner = "visibility";
  /// Sampling planners: iterations per query (what makes a route repeatable).
  long long iterations = 2000;
  /// Sampling planners: wall-clock cap per query, seconds; a query stopped by it may differ on a
  /// rerun, and the plan says so.
  double time_cap_s = 10.0;
  bool isDefault() const { return planner == "visibility"; }
};

}  // namespace coverbench
