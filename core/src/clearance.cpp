#include "coverbench/clearance.hpp"

#include <algorithm>

namespace coverbench {

ClearanceField::ClearanceField(const Wall& wall) : wall_(&wall) {
  obstacle_boxes_.reserve(wall.obstacles.size());
  for (const Obstacle& o : wall.obstacles) {
    if (o.type == ObstacleType::Circle) {
      Box b;
      b.add({o.center.x - o.radius, o.center.y - o.radius});
      b.add({o.center.x + o.radius, o.center.y + o.radius});
      obstacle_boxes_.push_back(b);
    } else {
      obstacle_boxes_.push_back(boundingBox(o.polygon));
    }
  }
}

double ClearanceField::obstacleDistance(std::size_t i, Point a, Point b) const {
  const Obstacle& o = wall_->obstacles[i];
  if (o.type == ObstacleType::Circle)
    return std::fmax(0.0, distancePointSegment(o.center, a, b) - o.radius);
  return distanceSegmentFilledRing(a, b, o.polygon);
}

SegmentClearance ClearanceField::measure(Point a, Point b, double obstacle_cutoff) const {
  SegmentClearance c;
  c.boundary_distance = distanceSegmentRingEdges(a, b, wall_->boundary);
  // A segment that does not touch the boundary is entirely inside or entirely outside it.
  c.inside = c.boundary_distance > 0.0 && pointInRing(a, wall_->boundary);
  Box seg;
  seg.add(a);
  seg.add(b);
  double best = obstacle_cutoff;
  for (std::size_t i = 0; i < obstacle_boxes_.size(); ++i) {
    if (boxDistance(seg, obstacle_boxes_[i]) >= best) continue;
    best = std::fmin(best, obstacleDistance(i, a, b));
  }
  c.obstacle_distance = best;
  return c;
}

bool ClearanceField::segmentFree(Point a, Point b, double radius, double clearance, double margin) const {
  // Squared distances throughout: this is the planners' hot path.
  const double need_obstacle = radius + clearance + margin;
  const double need_obstacle2 = need_obstacle * need_obstacle;
  Box seg;
  seg.add(a);
  seg.add(b);
  for (std::size_t i = 0; i < obstacle_boxes_.size(); ++i) {
    if (squaredBoxDistance(seg, obstacle_boxes_[i]) >= need_obstacle2) continue;
    const Obstacle& o = wall_->obstacles[i];
    if (o.type == ObstacleType::Circle) {
      const double reach = o.radius + need_obstacle;
      if (squaredDistancePointSegment(o.center, a, b) < reach * reach) return false;
      continue;
    }
    if (pointInRing(a, o.polygon)) return false;
    const Ring& ring = o.polygon;
    for (std::size_t k = 0, n = ring.size(); k < n; ++k)
      if (squaredDistanceSegmentSegment(a, b, ring[k], ring[(k + 1) % n]) < need_obstacle2) return false;
  }
  const Ring& ring = wall_->boundary;
  const std::size_t n = ring.size();
  const double need_boundary = radius + margin;
  const double need_boundary2 = need_boundary * need_boundary;
  for (std::size_t i = 0; i < n; ++i) {
    const Point p = ring[i], q = ring[(i + 1) % n];
    Box edge;
    edge.add(p);
    edge.add(q);
    if (squaredBoxDistance(seg, edge) >= need_boundary2) continue;
    if (squaredDistanceSegmentSegment(a, b, p, q) < need_boundary2) return false;
  }
  return pointInRing(a, ring);
}

}  // namespace coverbench
