#include "coverbench/path.hpp"

#include "coverbench/wall.hpp"

#include <cmath>

namespace coverbench {

void Path::moveTo(Point p, bool tool) {
  if (!bulge.empty()) return arcTo(p, 0.0, tool);
  if (!waypoints.empty() && waypoints.back() == p) return;
  if (!waypoints.empty()) tool_on.push_back(tool);
  waypoints.push_back(p);
}

double effectiveBulge(Point a, Point b, double bulge) {
  // A chord with a coordinate difference of kMinArcChord or more is at least that long (the
  // hypotenuse is never shorter than a side): no hypot for nearly every segment a path takes.
  if (std::fabs(bulge) < kMinArcBulge) return 0.0;
  if (std::fabs(a.x - b.x) >= kMinArcChord || std::fabs(a.y - b.y) >= kMinArcChord) return bulge;
  return distance(a, b) < kMinArcChord ? 0.0 : bulge;
}

void Path::arcTo(Point p, double b, bool tool) {
  if (!waypoints.empty() && waypoints.back() == p) return;
  if (!waypoints.empty()) {
    b = effectiveBulge(waypoints.back(), p, b);
    // The first arc gives every segment so far its 0; after it every segment has a bulge.
    if (b != 0.0 || !bulge.empty()) {
      bulge.resize(tool_on.size(), 0.0);
      bulge.push_back(b);
    }
    tool_on.push_back(tool);
  }
  waypoints.push_back(p);
}

bool Path::hasArcs() const {
  for (double b : bulge)
    if (b != 0.0) return true;
  return false;
}

ArcGeometry arcGeometry(Point a, Point b, double bulge) {
  // The centre lies on the chord's perpendicular bisector, (1 - b^2) / (4 b) chord lengths from
  // its midpoint (to the left of a -> b for b > 0); the radius follows from it.
  ArcGeometry g;
  const Point mid = (a + b) * 0.5, d = b - a;
  const double k = (1.0 - bulge * bulge) / (4.0 * bulge);
  g.centre = mid + Point{-d.y, d.x} * k;
  g.radius = norm(d) * (1.0 + bulge * bulge) / (4.0 * std::fabs(bulge));
  g.sweep = 4.0 * std::atan(bulge);
  return g;
}

double segmentLength(const Path& path, std::size_t i) {
  const Point a = path.waypoints[i], b = path.waypoints[i + 1];
  const double bulge = path.bulgeOf(i);
  if (bulge == 0.0) return distance(a, b);
  const ArcGeometry g = arcGeometry(a, b, bulge);
  return g.radius * std::fabs(g.sweep);
}

std::string toString(ToolShape shape) {
  switch (shape) {
    case ToolShape::Line: return "line";
    case ToolShape::Rectangle: return "rectangle";
    case ToolShape::Disk: break;
  }
  return "disk";
}

bool parseToolShape(const std::string& name, ToolShape& shape) {
  for (ToolShape k : {ToolShape::Disk, ToolShape::Line, ToolShape::Rectangle})
    if (name == toString(k)) {
      shape = k;
      return true;
    }
  return false;
}

std::string toolShapeProblem(const std::string& name) { return "must be disk, line or rectangle, got '" + shownBytes(name) + "'"; }

ToolParams circumscribedDisk(const ToolParams& tool) {
  ToolParams disk = tool;
  disk.tool_width = 2.0 * tool.reachRadius();
  disk.shape = ToolShape::Disk;
  disk.depth = 0.0;
  return disk;
}

std::string toolLabel(const ToolParams& tool) {
  const std::string shape = tool.shape == ToolShape::Disk ? "" : toString(tool.shape) + " ";
  const std::string depth = tool.isRectangle() ? ", d=" + shortNumber(tool.depth) + " m" : "";
  return shape + "s=" + shortNumber(tool.tool_width) + " m" + depth + ", c=" + shortNumber(tool.clearance) + " m";
}

std::string toolAndProfileLabel(const ToolParams& tool) {
  return toolLabel(tool) + (tool.profile.set() ? ", " + tool.profile.label() : "");
}

std::string toString(VehicleModel::Kind kind) {
  switch (kind) {
    case VehicleModel::Kind::Holonomic: return "holonomic";
    case VehicleModel::Kind::Gantry: return "gantry";
    case VehicleModel::Kind::Car: return "car";
  }
  return "holonomic";
}

bool parseVehicleKind(const std::string& name, VehicleModel::Kind& kind) {
  for (VehicleModel::Kind k : {VehicleModel::Kind::Holonomic, VehicleModel::Kind::Gantry, VehicleModel::Kind::Car})
    if (name == toString(k)) {
      kind = k;
      return true;
    }
  return false;
}

}  // namespace coverbench
