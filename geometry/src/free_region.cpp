#include "coverbench/free_region.hpp"

#include <algorithm>

#include "coverbench/region_ops.hpp"

namespace coverbench {

Wall rotateWall(const Wall& wall, double radians) {
  Wall out = wall;
  for (Point& p : out.boundary) p = rotate(p, radians);
  for (Obstacle& o : out.obstacles) {
    for (Point& p : o.polygon) p = rotate(p, radians);
    o.center = rotate(o.center, radians);
  }
  if (out.start) out.start = rotate(*out.start, radians);
  if (out.end) out.end = rotate(*out.end, radians);
  return out;
}

Region freeRegion(const Wall& wall, const ToolParams& tool, double margin, double arc_tolerance) {
  const double r = tool.radius();
  const Region boundary = regionFromRings({wall.boundary});
  const Region inner = offsetRegion(boundary, -(r + margin), arc_tolerance);
  if (inner.empty() || wall.obstacles.empty()) return inner;
  // Each obstacle as its own counter-clockwise polygon: the offset unites the grown polygons
  // itself (positive fill), so overlapping and touching obstacles need no union first.
  Region obstacles;
  for (const Obstacle& o : wall.obstacles) {
    Ring ring = o.type == ObstacleType::Circle ? circumscribedCircle(o.center, o.radius, arc_tolerance) : o.polygon;
    if (signedArea(ring) < 0.0) std::reverse(ring.begin(), ring.end());
    obstacles.push_back({std::move(ring), {}});
  }
  const Region blocked = offsetRegion(obstacles, r + tool.clearance + margin, arc_tolerance);
  // Common case, without a second sweep: one axis-aligned rectangle with every blocked part
  // strictly inside it and none enclosing a pocket. The difference is then the rectangle with
  // the blocked outlines as its holes (they are disjoint: they come out of one union).
  if (inner.size() == 1 && inner.front().holes.empty() && inner.front().outer.size() == 4) {
    const Ring& o = inner.front().outer;
    const Box box = boundingBox(o);
    bool rectangle = true;
    for (const Point& p : o) rectangle = rectangle && (p.x == box.min_x || p.x == box.max_x) && (p.y == box.min_y || p.y == box.max_y);
    bool inside = rectangle;
    for (const PolygonWithHoles& b : blocked) {
      if (!inside) break;
      const Box bb = boundingBox(b.outer);
      inside = b.holes.empty() && bb.min_x > box.min_x && bb.max_x < box.max_x && bb.min_y > box.min_y && bb.max_y < box.max_y;
    }
    if (inside) {
      PolygonWithHoles f{o, {}};
      for (const PolygonWithHoles& b : blocked) {
        f.holes.push_back(b.outer);
        std::reverse(f.holes.back().begin(), f.holes.back().end());  // holes run clockwise
      }
      return {f};
    }
  }
  return subtract(inner, blocked);
}

}  // namespace coverbench
