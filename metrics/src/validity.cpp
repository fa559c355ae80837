#include <cmath>

#include "coverbench/clearance.hpp"
#include "coverbench/metrics.hpp"

namespace coverbench {

Validity checkValidity(const Wall& wall, const ToolParams& tool, const Path& path, const VehicleModel& vehicle) {
  Validity v;
  const ClearanceField field(wall);
  const double r = tool.radius();
  const std::size_t n = path.waypoints.size();
  // A gantry's lifted move: the disk at both ends inside the wall's bounding box (then the whole
  // move is, the box being convex).
  const Box frame = boundingBox(wall.boundary);
  auto inFrame = [&](Point p) {
    return p.x - r >= frame.min_x - kValidityTolerance && p.x + r <= frame.max_x + kValidityTolerance &&
           p.y - r >= frame.min_y - kValidityTolerance && p.y + r <= frame.max_y + kValidityTolerance;
  };
  auto lifted = [&](std::size_t segment, Point a, Point b) {
    const bool outside = !inFrame(a) || !inFrame(b);
    v.outside_boundary += outside;
    v.violations += outside;
    if (outside && v.violating.size() < kMaxListedViolations) v.violating.push_back(segment);
  };
  auto check = [&](std::size_t segment, Point a, Point b) {
    const SegmentClearance c = field.measure(a, b, std::fmax(v.min_clearance, tool.clearance) + r);
    const double boundary_gap = c.inside ? c.boundary_distance - r : -c.boundary_distance - r;
    const double obstacle_gap = c.obstacle_distance - r;
    v.min_boundary_gap = std::fmin(v.min_boundary_gap, boundary_gap);
    v.min_clearance = std::fmin(v.min_clearance, obstacle_gap);
    const bool outside = boundary_gap < -kValidityTolerance;
    const bool close = obstacle_gap < tool.clearance - kValidityTolerance;
    v.outside_boundary += outside;
    v.too_close += close;
    if ((outside || close) && v.violating.size() < kMaxListedViolations) v.violating.push_back(segment);
    v.violations += outside || close;
  };
  if (n == 1) check(0, path.waypoints[0], path.waypoints[0]);
  const bool lifts = vehicle.liftsTool();
  for (std::size_t i = 0; i + 1 < n; ++i)
    if (lifts && !path.tool_on[i])
      lifted(i, path.waypoints[i], path.waypoints[i + 1]);
    else
      check(i, path.waypoints[i], path.waypoints[i + 1]);
  v.valid = v.violations == 0;
  return v;
}

Lengths pathLengths(const Path& path) {
  Lengths l;
  for (std::size_t i = 0; i + 1 < path.waypoints.size(); ++i) {
    const double d = distance(path.waypoints[i], path.waypoints[i + 1]);
    l.total += d;
    (path.tool_on[i] ? l.cover : l.transit) += d;
  }
  return l;
}

}  // namespace coverbench
